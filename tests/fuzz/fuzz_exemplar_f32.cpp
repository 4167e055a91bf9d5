// Fuzz target: the raw float32 exemplar reader (.f32 + JSON sidecar, docs/formats.md).
// Input: u16 sidecar length, the sidecar, then the raw samples.
#include "fuzz_support.h"
#include "terrasynth/heightfield_io.h"

using namespace terrasynth;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string sidecar, raw;
    fuzz::splitInput(data, size, &sidecar, &raw);
    const std::string dir = fuzz::scratchDir();
    fuzz::writeFile(dir + "/e.f32", raw);
    fuzz::writeFile(dir + "/e.json", sidecar);
    fuzz::writeFile(dir + "/mask.png", raw);
    auto exemplar = readExemplar(dir + "/e.f32");
    if (exemplar && !validateHeightfield(exemplar->field)) __builtin_trap();
    return 0;
}
