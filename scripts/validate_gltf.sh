#!/bin/sh
# Validates glTF 2.0 files (.gltf with its external .bin, or .glb) with the Khronos glTF validator
# (npm package gltf-validator, pinned in scripts/package.json; install once with
# `npm ci --prefix scripts`). Prints the issue counts and every error; exits 0 only when every file
# has zero errors, 1 on validation errors, 2 when the validator is not installed, 3 on bad usage.
#   scripts/validate_gltf.sh out.glb [more.gltf ...]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
if [ "$#" -lt 1 ]; then
    echo "usage: $0 FILE.glb|FILE.gltf ..." >&2
    exit 3
fi
if ! command -v node >/dev/null 2>&1; then
    echo "validate_gltf: node is not installed" >&2
    exit 2
fi
if [ ! -f "$here/node_modules/gltf-validator/package.json" ]; then
    echo "validate_gltf: gltf-validator is missing; run: npm ci --prefix $here" >&2
    exit 2
fi
NODE_PATH="$here/node_modules" exec node - "$@" <<'JS'
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 0,
        writeTimestamp: false,
        externalResourceFunction: (uri) => new Promise((resolve, reject) => {
            fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)),
                        (err, data) => err ? reject(err.toString()) : resolve(new Uint8Array(data)));
        }),
    });
    const i = report.issues;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints` +
                ` (validator ${report.validatorVersion})`);
    for (const m of i.messages) {
        if (m.severity === 0) console.log(`  error ${m.code} at ${m.pointer || m.offset}: ${m.message}`);
    }
    return i.numErrors;
}

(async () => {
    let errors = 0;
    for (const file of process.argv.slice(2)) {
        try {
            errors += await validate(file);
        } catch (e) {
            console.log(`${file}: could not be validated: ${e}`);
            errors += 1;
        }
    }
    process.exit(errors === 0 ? 0 : 1);
})();
JS
