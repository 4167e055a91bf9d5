// Fuzz target: the exemplar reader for a 16-bit PNG with its JSON sidecar (the format of
// data/exemplars, docs/formats.md), and a type-mask PNG the sidecar may name ("mask.png").
// Input: u16 sidecar length, the sidecar, then the PNG. An empty sidecar part means "no sidecar":
// the plain-PNG path with a given vertical scale.
#include <cstdio>

#include "fuzz_support.h"
#include "terrasynth/heightfield_io.h"

using namespace terrasynth;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string sidecar, png;
    fuzz::splitInput(data, size, &sidecar, &png);
    const std::string dir = fuzz::scratchDir();
    fuzz::writeFile(dir + "/e.png", png);
    fuzz::writeFile(dir + "/mask.png", png);
    PlainPngScale plain;
    plain.meters_per_pixel = 30.0;
    if (sidecar.empty()) std::remove((dir + "/e.json").c_str());
    else fuzz::writeFile(dir + "/e.json", sidecar);
    auto exemplar = readExemplar(dir + "/e.png", &plain);
    if (exemplar) {
        // What the reader promises: a valid field, and a mask of the field's size when there is one.
        if (!validateHeightfield(exemplar->field)) __builtin_trap();
        if (!exemplar->type_mask.empty() && exemplar->type_mask.size() != exemplar->field.size()) __builtin_trap();
    }
    auto image8 = readPng8(dir + "/mask.png");
    if (image8 && image8->samples.size() != size_t(image8->width) * image8->height * image8->channels) __builtin_trap();
    return 0;
}
