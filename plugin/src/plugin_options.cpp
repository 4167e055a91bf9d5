#include "terrasynth_plugin/plugin_options.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <sstream>

#include "terrasynth/checked_number.h"
#include "terrasynth/limits.h"

namespace terrasynth::plugin {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

bool parseInt(const std::string& v, long long lo, long long hi, long long& out) {
    errno = 0;
    char* end = nullptr;
    const long long x = std::strtoll(v.c_str(), &end, 10);
    if (errno || end == v.c_str() || *end || x < lo || x > hi) return false;
    out = x;
    return true;
}

}  // namespace

Result<PluginOptions> parsePluginOptions(const std::string& option_string) {
    PluginOptions o;
    std::string text = option_string;
    std::replace_if(text.begin(), text.end(), [](char c) { return c == ',' || c == ';'; }, ' ');
    std::istringstream in(text);
    std::string token;
    while (in >> token) {
        const size_t eq = token.find('=');
        if (eq == std::string::npos) continue;
        const std::string key = lower(token.substr(0, eq)), value = token.substr(eq + 1);
        auto bad = [&](const std::string& expect) {
            return Status::error("option " + token.substr(0, eq) + "=" + value + ": expected " + expect);
        };
        // Every number through the check the command-line flags use: finite, in [lo, hi].
        double d = 0.0;
        auto number = [&](double lo, double hi) {
            auto parsed = parseFiniteNumber(value, lo, hi);
            if (parsed) d = *parsed;
            return parsed.isOk();
        };
        long long i = 0;
        if (key == "tilesize") {
            if (!parseInt(value, 8, 2048, i)) return bad("an integer in [8, 2048]");
            o.node.tile_size = static_cast<int>(i);
        } else if (key == "maxlevel") {
            if (!parseInt(value, 0, 20, i)) return bad("an integer in [0, 20]");
            o.node.max_level = static_cast<int>(i);
            o.max_level_given = true;
        } else if (key == "minlevel") {
            if (!parseInt(value, 0, 20, i)) return bad("an integer in [0, 20]");
            o.node.min_level = static_cast<int>(i);
        } else if (key == "meshstep") {
            if (!parseInt(value, 1, 1024, i)) return bad("an integer in [1, 1024]");
            o.node.mesh_step = static_cast<int>(i);
        } else if (key == "pixelerror") {
            if (!number(0.01, 1e4)) return bad(finiteRangeText(0.01, 1e4));
            o.node.pixel_error = static_cast<float>(d);
        } else if (key == "viewradius") {
            if (!number(0, 1e9)) return bad("metres, " + finiteRangeText(0, 1e9));
            o.node.view_radius_m = d;
        } else if (key == "threads") {
            if (!parseInt(value, 0, 256, i)) return bad("an integer in [0, 256]");
            o.node.threads = static_cast<int>(i);
        } else if (key == "cachemb") {
            if (!number(1, 1e7)) return bad("MiB, " + finiteRangeText(1, 1e7));
            o.node.cache_mb = d;
        } else if (key == "mergesperframe") {
            if (!parseInt(value, 1, 100000, i)) return bad("an integer >= 1");
            o.node.max_merges_per_frame = static_cast<int>(i);
        } else if (key == "mergebudgetms") {
            if (!number(1e-3, 1e4)) return bad("milliseconds, " + finiteRangeText(1e-3, 1e4));
            o.node.merge_budget_ms = d;
        } else if (key == "skirt") {
            if (!number(0, 1000)) return bad("sample spacings, " + finiteRangeText(0, 1000));
            o.node.skirt_extra_spacings = static_cast<float>(d);
        } else if (key == "seed") {
            if (!parseInt(value, 0, 0xffffffffll, i)) return bad("an unsigned 32-bit integer");
            o.seed = static_cast<uint32_t>(i);
        } else if (key == "backend") {
            const std::string b = lower(value);
            if (b == "opencl") o.synthesizer.backend = SynthesisBackend::OpenCL;
            else if (b == "reference") o.synthesizer.backend = SynthesisBackend::Reference;
            else return bad("opencl or reference");
        } else if (key == "device") {
            o.synthesizer.device = value;
        } else if (key == "geomorph") {
            if (!parseInt(value, 0, 1, i)) return bad("0 or 1");
            o.node.geomorph = i != 0;
        } else if (key == "preload") {
            if (!parseInt(value, 0, 1, i)) return bad("0 or 1");
            o.preload = i != 0;
        } else if (key == "sunazimuth") {
            if (!number(-360, 360)) return bad("degrees, " + finiteRangeText(-360, 360));
            o.sun_azimuth_deg = static_cast<float>(d);
        } else if (key == "sunelevation") {
            if (!number(0, 90)) return bad("degrees, " + finiteRangeText(0, 90));
            o.sun_elevation_deg = static_cast<float>(d);
        } else if (key == "snowline") {
            if (!number(-limits::kMaxAbsHeightM, limits::kMaxAbsHeightM))
                return bad("metres, " + finiteRangeText(-limits::kMaxAbsHeightM, limits::kMaxAbsHeightM));
            o.snow_line_m = static_cast<float>(d);
        } else if (key == "fog") {
            if (!number(0, 1e9)) return bad("metres, " + finiteRangeText(0, 1e9));
            o.fog_m = static_cast<float>(d);
        } else if (key == "typecolors") {
            if (!parseInt(value, 0, 1, i)) return bad("0 or 1");
            o.type_colors = i != 0;
        } else if (key == "preloadlevel") {
            if (!parseInt(value, 0, 20, i)) return bad("an integer in [0, 20]");
            o.preload_level = static_cast<int>(i);
        }
    }
    if (Status s = validateOptions(o.node); !s) return s;
    return o;
}

}  // namespace terrasynth::plugin
