// Fuzz target: the database loader (loadDatabase), and the synthesis kernels on whatever it accepts.
// Input byte 0 picks the mode: even = the rest is the whole file; odd = the rest is a payload that
// gets a valid header and a recomputed checksum, so the fuzzer gets past the checksum to the
// structural checks. A database the loader accepts is synthesized by the reference backend (a small
// window, plain and with painted types), which must stay in bounds: the loader is the only guard.
#include <cstring>

#include "fuzz_support.h"
#include "terrasynth/database.h"
#include "terrasynth/synthesizer.h"

using namespace terrasynth;

namespace {

uint64_t fnv1a(const std::string& bytes) {
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
    return h;
}

// The file format of database_file.cpp: magic, version, reserved, payload size, checksum, payload.
std::string withHeader(const std::string& payload) {
    std::string file("TSYNDB01", 8);
    const uint32_t version = ExemplarDatabase::kFormatVersion, reserved = 0;
    const uint64_t size = payload.size(), checksum = fnv1a(payload);
    file.append(reinterpret_cast<const char*>(&version), 4);
    file.append(reinterpret_cast<const char*>(&reserved), 4);
    file.append(reinterpret_cast<const char*>(&size), 8);
    file.append(reinterpret_cast<const char*>(&checksum), 8);
    return file + payload;
}

void synthesize(const std::shared_ptr<const ExemplarDatabase>& db) {
    SynthesizerOptions options;
    options.backend = SynthesisBackend::Reference;
    auto synthesizer = Synthesizer::create(db, options);
    if (!synthesizer) return;
    SynthesisParams params;
    params.seed = 7;
    const PixelWindow window{-3, 5, 4, 3};
    auto plain = (*synthesizer)->synthesize(window, params, 0, /*want_sources=*/true);
    if (plain && plain->heights.size() != 12) __builtin_trap();
    // Every pixel painted with the last type: candidates of other types are rejected and seeding
    // (or the fallback) must still find a valid coordinate.
    auto constraints = std::make_shared<SynthesisConstraints>();
    constraints->types.x = -40, constraints->types.y = -40;
    constraints->types.width = constraints->types.height = 96;
    constraints->types.types.assign(96 * 96, static_cast<uint8_t>(db->type_names.size() - 1));
    constraints->points.push_back(PointConstraint{0.5, 6.0, 1500.0f, 0.0f, 10.0f, 8.0f, 0.0f});
    params.constraints = constraints;
    params.first_constrained_level = 0;
    (void)(*synthesizer)->synthesize(window, params, 0, true);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    std::string rest(reinterpret_cast<const char*>(data + 1), size - 1);
    const std::string path = fuzz::scratchDir() + "/db.tsdb";
    fuzz::writeFile(path, (data[0] & 1) ? withHeader(rest) : rest);
    auto db = loadDatabase(path);
    if (db) synthesize(*db);
    return 0;
}
