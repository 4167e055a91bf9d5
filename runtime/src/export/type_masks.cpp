// Terrain-type masks for texture splatting, from the per-pixel types of a coordinate map.
#include <algorithm>
#include <cctype>
#include <numeric>

#include "terrasynth/gltf_export.h"
#include "terrasynth/heightfield_io.h"

namespace terrasynth {

namespace {

std::string sanitise(const std::string& name, size_t index) {
    std::string out;
    for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return out.empty() ? "type" + std::to_string(index) : out;
}

// Separable box blur of a 0/1 mask (clamped edges) giving weights in [0, 1].
std::vector<float> boxBlur(const std::vector<float>& in, int w, int h, int r) {
    std::vector<float> tmp(in.size()), out(in.size());
    const float norm = 1.0f / (2 * r + 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float s = 0.0f;
            for (int k = -r; k <= r; ++k) s += in[size_t(y) * w + std::clamp(x + k, 0, w - 1)];
            tmp[size_t(y) * w + x] = s * norm;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float s = 0.0f;
            for (int k = -r; k <= r; ++k) s += tmp[size_t(std::clamp(y + k, 0, h - 1)) * w + x];
            out[size_t(y) * w + x] = s * norm;
        }
    return out;
}

}  // namespace

std::string typeMaskPath(const std::string& prefix, const std::vector<std::string>& type_names, size_t index,
                         const std::string& suffix) {
    const std::string path = prefix + sanitise(type_names[index], index) + suffix + ".png";
    // Two names that sanitise alike ("a b", "a_b") must not write one file twice.
    for (size_t earlier = 0; earlier < index; ++earlier)
        if (prefix + sanitise(type_names[earlier], earlier) + suffix + ".png" == path)
            return prefix + sanitise(type_names[index], index) + "_" + std::to_string(index) + suffix + ".png";
    return path;
}

Result<std::vector<std::string>> stageTypeMasks(FileTransaction& transaction, const std::string& prefix, int width,
                                                int height, const std::vector<uint8_t>& types,
                                                const std::vector<std::string>& type_names,
                                                const TypeMaskOptions& options, const std::string& name_suffix) {
    if (width < 1 || height < 1 || types.size() != size_t(width) * height)
        return Status::error(prefix + ": type map size does not match " + std::to_string(width) + "x" + std::to_string(height));
    if (options.blur_radius < 0) return Status::error("blur_radius: must not be negative");
    const size_t n = types.size(), count = type_names.size();
    std::vector<std::vector<uint8_t>> masks(count, std::vector<uint8_t>(n, 0));
    if (options.blur_radius == 0) {
        for (size_t p = 0; p < n; ++p)
            if (types[p] < count) masks[types[p]][p] = 255;
    } else {
        std::vector<std::vector<float>> weights(count);
        for (size_t t = 0; t < count; ++t) {
            std::vector<float> hard(n, 0.0f);
            for (size_t p = 0; p < n; ++p) hard[p] = types[p] == t ? 1.0f : 0.0f;
            weights[t] = boxBlur(hard, width, height, options.blur_radius);
        }
        // Largest remainder: floors first, then the leftover units to the largest fractions, so the
        // masks sum to exactly 255 wherever any type is known.
        std::vector<size_t> order(count);
        std::vector<float> fraction(count);
        for (size_t p = 0; p < n; ++p) {
            float total = 0.0f;
            for (size_t t = 0; t < count; ++t) total += weights[t][p];
            if (total <= 0.0f) continue;
            int assigned = 0;
            for (size_t t = 0; t < count; ++t) {
                const float share = weights[t][p] / total * 255.0f;
                masks[t][p] = static_cast<uint8_t>(share);
                fraction[t] = share - masks[t][p];
                assigned += masks[t][p];
            }
            std::iota(order.begin(), order.end(), 0);
            std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return fraction[a] > fraction[b]; });
            for (size_t k = 0; assigned < 255 && k < count; ++k, ++assigned) ++masks[order[k]][p];
        }
    }
    std::vector<std::string> paths;
    for (size_t t = 0; t < count; ++t) {
        const std::string path = typeMaskPath(prefix, type_names, t, name_suffix);
        if (Status s = stagePng8(transaction, path, width, height, 1, masks[t]); !s) return s;
        paths.push_back(path);
    }
    return paths;
}

Result<std::vector<std::string>> writeTypeMasks(const std::string& prefix, int width, int height,
                                                const std::vector<uint8_t>& types,
                                                const std::vector<std::string>& type_names,
                                                const TypeMaskOptions& options) {
    FileTransaction transaction;
    auto paths = stageTypeMasks(transaction, prefix, width, height, types, type_names, options);
    if (!paths) return paths;
    if (Status s = transaction.commit(); !s) return s;
    return paths;
}

}  // namespace terrasynth
