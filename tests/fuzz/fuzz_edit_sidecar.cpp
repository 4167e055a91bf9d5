// Fuzz target: the edited-heights sidecar reader (project/edit_sidecar.h: decodeEditSidecar and
// sidecarDigest) and IncrementalTerrain::restore on whatever it accepts, the path every `.heights`
// file and autosave takes into Terrain and EditSession. Input byte 0 picks the mode:
//   0 mod 3: the rest is the whole file;
//   1 mod 3: the rest is a file without its last 8 bytes: the checksum is recomputed and appended,
//            so the fuzzer gets past it to the header and the blobs;
//   2 mod 3: the rest is a list of edits (u16 little-endian offset, byte) applied to a real sidecar
//            of a small session (24x20 extent with its synthesis history), checksum recomputed, so
//            mutations reach the history blobs and restore's atlas checks.
// A sidecar that decodes must encode and decode again to the same bytes; one that restores must
// report the extent it was given.
#include <cmath>
#include <cstring>

#include "fuzz_support.h"
#include "project/edit_sidecar.h"
#include "terrasynth/database.h"
#include "terrasynth/incremental.h"
#include "terrasynth/synthesizer.h"

using namespace terrasynth;

namespace {

std::shared_ptr<const ExemplarDatabase> database;
std::unique_ptr<Synthesizer> synthesizer;
std::string reference_file;  // a real sidecar, checksum included
const PixelWindow kExtent{-8, 4, 24, 20};

uint64_t checksum(const std::string& bytes) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    return h;
}

std::string withChecksum(std::string body) {
    const uint64_t sum = checksum(body);
    body.append(reinterpret_cast<const char*>(&sum), 8);
    return body;
}

SynthesisParams params() {
    SynthesisParams p;
    p.seed = 11;
    return p;
}

void setUp() {
    std::vector<Exemplar> exemplars(1);
    exemplars[0].info.name = "ridges";
    exemplars[0].info.terrain_class = "alpine ranges";
    exemplars[0].field = Heightfield(40, 40, 90.0);
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 40; ++x)
            exemplars[0].field.at(x, y) = static_cast<float>(800.0 + 300.0 * std::sin(0.3 * x) * std::cos(0.2 * y) + 7.0 * x);
    DatabaseBuildOptions options;
    options.levels = 2;
    options.threads = 1;
    auto db = buildDatabase(std::move(exemplars), options);
    if (!db) __builtin_trap();
    database = *db;
    SynthesizerOptions so;
    so.backend = SynthesisBackend::Reference;
    auto s = Synthesizer::create(database, so);
    if (!s) __builtin_trap();
    synthesizer = std::move(s.value());
    auto terrain = IncrementalTerrain::create(*synthesizer, kExtent, params());
    if (!terrain) __builtin_trap();
    project::EditSidecar sidecar;
    sidecar.digest = 0x0123456789abcdefull;
    sidecar.extent = kExtent;
    sidecar.heights = terrain->heights().heights;
    sidecar.frozen = terrain->frozenMask();
    sidecar.history = terrain->history();
    sidecar.lifts.points = {1.5f};
    sidecar.lifts.tilts = {{0.1f, -0.2f}};
    sidecar.lifts.curves = {{0.0f, 2.0f, 1.0f}};
    sidecar.reference.json = "{}";
    reference_file = project::encodeEditSidecar(sidecar);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    setUp();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (!database) setUp();
    if (size < 1) return 0;
    const std::string rest(reinterpret_cast<const char*>(data + 1), size - 1);
    std::string file;
    switch (data[0] % 3) {
        case 0: file = rest; break;
        case 1: file = withChecksum(rest); break;
        default: {
            file = reference_file.substr(0, reference_file.size() - 8);
            for (size_t k = 0; k + 3 <= rest.size(); k += 3) {
                const size_t at = (static_cast<uint8_t>(rest[k]) | static_cast<uint8_t>(rest[k + 1]) << 8) % file.size();
                file[at] = rest[k + 2];
            }
            file = withChecksum(file);
        }
    }
    (void)project::sidecarDigest(file, "fuzz.heights");
    auto decoded = project::decodeEditSidecar(file, "fuzz.heights", /*with_history=*/true);
    if (!decoded) return 0;
    const std::string again = project::encodeEditSidecar(*decoded);
    auto redecoded = project::decodeEditSidecar(again, "again.heights", true);
    if (!redecoded || project::encodeEditSidecar(*redecoded) != again) __builtin_trap();
    if (decoded->extent != kExtent) return 0;
    Heightfield heights(kExtent.width, kExtent.height, database->meters_per_pixel);
    heights.heights = decoded->heights;
    auto restored = IncrementalTerrain::restore(*synthesizer, kExtent, params(), std::move(heights),
                                                std::move(decoded->frozen), std::move(decoded->history));
    if (restored && restored->extent() != kExtent) __builtin_trap();
    return 0;
}
