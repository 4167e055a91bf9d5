// The baked world on a bare ellipsoid: no Cesium ion token, no imagery, no terrain service, so the
// page asks nothing of any host but the one that serves it. window.terrasynthViewer tells a headless
// browser (screenshot.mjs) when every tile the view needs is loaded.
const Cesium = window.Cesium;
const state = { loaded: false, tilesLoadedEvents: 0, error: null, clearColor: [111, 143, 176] };
window.terrasynthViewer = state;

try {
  const viewer = new Cesium.Viewer('view', {
    baseLayer: false,
    terrainProvider: new Cesium.EllipsoidTerrainProvider(),
    baseLayerPicker: false, geocoder: false, homeButton: false, sceneModePicker: false,
    navigationHelpButton: false, animation: false, timeline: false, fullscreenButton: false,
    infoBox: false, selectionIndicator: false, skyBox: false, skyAtmosphere: false,
    contextOptions: { webgl: { preserveDrawingBuffer: true } },
  });
  const scene = viewer.scene;
  scene.globe.show = false;  // the world is the only thing drawn, over the clear colour
  scene.fog.enabled = false;
  if (scene.sun) scene.sun.show = false;
  if (scene.moon) scene.moon.show = false;
  const [r, g, b] = state.clearColor;
  scene.backgroundColor = Cesium.Color.fromBytes(r, g, b, 255);

  const tileset = await Cesium.Cesium3DTileset.fromUrl('/world/tileset.json', { maximumScreenSpaceError: 2 });
  // The bake's frame is local (x east, y north, z up, metres): stand it on the ellipsoid somewhere,
  // where its axes are that place's east, north and up.
  const enu = Cesium.Transforms.eastNorthUpToFixedFrame(Cesium.Cartesian3.fromDegrees(11.0, 47.0, 0.0));
  tileset.modelMatrix = enu;
  // A fixed light from the north-west, whatever the clock says, and a tint by slope (the tiles carry
  // no colours): flat ground green, steep ground rock.
  const fromNorthWest = Cesium.Cartesian3.normalize(new Cesium.Cartesian3(1.0, -1.0, -1.2), new Cesium.Cartesian3());
  scene.light = new Cesium.DirectionalLight({
    direction: Cesium.Matrix4.multiplyByPointAsVector(enu, fromNorthWest, new Cesium.Cartesian3()), intensity: 2.5,
  });
  tileset.imageBasedLighting.imageBasedLightingFactor = new Cesium.Cartesian2(0.25, 0.25);
  tileset.customShader = new Cesium.CustomShader({
    varyings: { v_up: Cesium.VaryingType.FLOAT },
    vertexShaderText: `void vertexMain(VertexInput vsInput, inout czm_modelVertexOutput vsOutput) {
      v_up = vsInput.attributes.normalMC.y;  // glTF's +Y is up
    }`,
    fragmentShaderText: `void fragmentMain(FragmentInput fsInput, inout czm_modelMaterial material) {
      material.diffuse = mix(vec3(0.50, 0.46, 0.41), vec3(0.35, 0.46, 0.27), smoothstep(0.90, 0.985, v_up));
    }`,
  });
  scene.primitives.add(tileset);
  // Looking north-east and down from inside the world's bounding sphere, so the terrain fills the view.
  const sphere = tileset.boundingSphere;
  viewer.camera.viewBoundingSphere(sphere, new Cesium.HeadingPitchRange(Cesium.Math.toRadians(20.0), Cesium.Math.toRadians(-30.0),
    sphere.radius * 0.45));
  viewer.camera.lookAtTransform(Cesium.Matrix4.IDENTITY);
  tileset.allTilesLoaded.addEventListener(() => {
    state.tilesLoadedEvents += 1;
    state.loaded = true;
  });
} catch (e) {
  state.error = String(e && e.message ? e.message + "\n" + e.stack : e);
}
