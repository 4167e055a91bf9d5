#include "source_usage_report.h"

#include <cmath>
#include <cstdio>

#include "terrasynth/heightfield_io.h"
#include "terrasynth/source_usage.h"

namespace terrasynth::cli {
namespace {

Result<nlohmann::json> readSidecar(const std::string& sources_png) {
    const std::string path = sources_png.substr(0, sources_png.find_last_of('.')) + ".json";
    auto bytes = readFileBytes(path);
    if (!bytes) return bytes.status();
    auto side = nlohmann::json::parse(bytes.value(), nullptr, false);
    if (side.is_discarded() || !side.contains("exemplars") || !side["exemplars"].is_array() ||
        !side.contains("exemplar_meters_per_pixel") || !side["exemplar_meters_per_pixel"].is_number())
        return Status::error(path + ": not a sources sidecar (needs \"exemplars\" and \"exemplar_meters_per_pixel\")");
    return side;
}

}  // namespace

Result<nlohmann::json> measureSourcesMap(const std::string& sources_png) {
    auto side = readSidecar(sources_png);
    if (!side) return side.status();
    auto map = readPng16(sources_png);
    if (!map) return map.status();
    if (map->channels != 3) return Status::error(sources_png + ": expected a 16-bit RGB sources map");
    const double spacing = side.value()["exemplar_meters_per_pixel"].get<double>();
    std::vector<Heightfield> exemplars;
    nlohmann::json names = nlohmann::json::array();
    for (const auto& e : side.value()["exemplars"]) {
        const std::string path = e.value("path", "");
        auto exemplar = readExemplar(path);
        if (!exemplar) return exemplar.status().withContext(sources_png + ": exemplar " + e.value("name", path));
        // The database resamples every exemplar to its spacing (coarser levels are its pyramid;
        // resampling stands in for it there).
        exemplars.push_back(resampleToSpacing(exemplar->field, spacing));
        names.push_back(e.value("name", path));
    }
    const size_t n = static_cast<size_t>(map->width) * map->height;
    std::vector<float> sx(n), sy(n);
    std::vector<uint8_t> se(n);
    for (size_t i = 0; i < n; ++i) {
        sx[i] = map->samples[3 * i], sy[i] = map->samples[3 * i + 1];
        se[i] = static_cast<uint8_t>(std::min<uint16_t>(map->samples[3 * i + 2], 255));
    }
    auto usage = measureSourceUsage(exemplars, sx, sy, se);
    if (!usage) return usage.status().withContext(sources_png);
    nlohmann::json report = {{"file", sources_png}, {"width", map->width}, {"height", map->height},
                             {"exemplar_meters_per_pixel", spacing}, {"flat_fraction", 0.3}, {"relief_window", 9}};
    for (size_t e = 0; e < usage->size(); ++e) {
        const ExemplarUsage& u = (*usage)[e];
        report["exemplars"].push_back({{"name", names[e]},
                                       {"output_share", u.output_share},
                                       {"exemplar_share", u.exemplar_share},
                                       {"flattest_share", std::isfinite(u.flattest_share) ? nlohmann::json(u.flattest_share)
                                                                                          : nlohmann::json(nullptr)}});
    }
    return report;
}

void printSourcesReport(const nlohmann::json& report) {
    std::printf("%s: %dx%d output pixels drawn from exemplars at %.4g m/pixel\n",
                report["file"].get<std::string>().c_str(), report["width"].get<int>(), report["height"].get<int>(),
                report["exemplar_meters_per_pixel"].get<double>());
    std::printf("  %-28s %12s %15s %10s %22s\n", "exemplar", "output share", "exemplar share", "ratio",
                "from its flattest 30%");
    for (const auto& e : report["exemplars"]) {
        const double out = e["output_share"], own = e["exemplar_share"];
        std::printf("  %-28s %11.1f%% %14.1f%% %10.2f", e["name"].get<std::string>().c_str(), 100.0 * out, 100.0 * own,
                    own > 0 ? out / own : 0.0);
        if (e["flattest_share"].is_null()) std::printf(" %22s\n", "-");
        else std::printf(" %21.1f%%\n", 100.0 * e["flattest_share"].get<double>());
    }
    std::printf("  (an unbiased synthesis keeps ratio near 1 without type painting and draws ~30%% from the flattest 30%%)\n");
}

}  // namespace terrasynth::cli
