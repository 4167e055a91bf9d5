#include "core/sidecar.h"

#include <algorithm>
#include <cmath>

#include "terrasynth/heightfield_io.h"
#include "terrasynth/limits.h"

namespace terrasynth::detail {

Result<nlohmann::json> readJsonFile(const std::string& path) {
    auto bytes = readFileBytes(path, limits::kMaxJsonBytes);
    if (!bytes) return bytes.status();
    auto j = parseJson(bytes.value(), path);
    if (!j) return j.status();
    if (!j->is_object()) return Status::error(path + ": expected a JSON object at the top level");
    return j;
}

Result<double> requireNumber(const nlohmann::json& j, const char* key, const std::string& file) {
    auto it = j.find(key);
    if (it == j.end()) return Status::error(file + ": missing field \"" + key + "\"");
    if (!it->is_number()) return Status::error(file + ": field \"" + key + "\" must be a number");
    const double v = it->get<double>();
    if (!std::isfinite(v)) return Status::error(file + ": field \"" + key + "\" is not finite");
    return v;
}

Status readSpacing(const nlohmann::json& j, const std::string& file, double* x, double* y) {
    auto it = j.find("meters_per_pixel");
    if (it == j.end()) return Status::error(file + ": missing field \"meters_per_pixel\"");
    if (it->is_number()) {
        *x = *y = it->get<double>();
    } else if (it->is_array() && it->size() == 2 && (*it)[0].is_number() && (*it)[1].is_number()) {
        *x = (*it)[0].get<double>();
        *y = (*it)[1].get<double>();
    } else {
        return Status::error(file + ": field \"meters_per_pixel\" must be a number or [x, y]");
    }
    if (!(*x > 0.0 && *y > 0.0 && *x <= 1e5 && *y <= 1e5))
        return Status::error(file + ": field \"meters_per_pixel\" must be in (0, 100000]");
    return Status::ok();
}

void readProvenance(const nlohmann::json& j, ExemplarInfo* info) {
    auto text = [&](const char* key) {
        auto it = j.find(key);
        return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
    };
    info->terrain_class = text("terrain_class");
    info->source = text("source");
    info->license = text("license");
}

Status readTypeMask(const nlohmann::json& j, const std::string& sidecar, Exemplar* exemplar) {
    auto it = j.find("type_mask");
    if (it == j.end()) return Status::ok();
    if (!it->is_string()) return Status::error(sidecar + ": field \"type_mask\" must be a file name");
    const std::string mask_path = detail::resolveRelative(detail::folderOf(sidecar), it->get<std::string>());
    auto mask = readPng8(mask_path);
    if (!mask) return mask.status();
    if (mask->width != exemplar->field.width || mask->height != exemplar->field.height || mask->channels != 1)
        return Status::error(mask_path + ": type mask must be 8-bit gray of the exemplar's size");
    exemplar->type_mask = std::move(mask->samples);
    auto names = j.find("type_names");
    if (names != j.end() && names->is_array())
        for (const auto& n : *names) exemplar->type_mask_names.push_back(n.is_string() ? n.get<std::string>() : "");
    for (uint8_t v : exemplar->type_mask)
        if (v == 255) return Status::error(mask_path + ": value 255 is reserved (use 0..254)");
    return Status::ok();
}

}  // namespace terrasynth::detail
