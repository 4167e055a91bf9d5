// The versioned database cache file (docs/formats.md):
//   "TSYNDB01" | u32 version | u32 reserved | u64 payload bytes | u64 FNV-1a of payload | payload
// All integers little-endian. A reader checks every length against the bytes that remain, so a
// truncated or corrupt file is reported, never partially trusted.
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <type_traits>

#include "db/db_internal.h"
#include "terrasynth/limits.h"

namespace terrasynth {
namespace {

constexpr char kMagic[8] = {'T', 'S', 'Y', 'N', 'D', 'B', '0', '1'};
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;

uint64_t fnv1a(const char* data, size_t size, uint64_t h = 1469598103934665603ull) {
    for (size_t i = 0; i < size; ++i) {
        h ^= static_cast<unsigned char>(data[i]);
        h *= 1099511628211ull;
    }
    return h;
}

class Writer {
public:
    template <class T>
    void pod(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    void text(const std::string& s) {
        pod<uint64_t>(s.size());
        bytes_ += s;
    }
    template <class T>
    void array(const std::vector<T>& v) {
        pod<uint64_t>(v.size());
        if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
    std::string& bytes() { return bytes_; }

private:
    std::string bytes_;
};

class Reader {
public:
    Reader(const char* data, size_t size) : data_(data), size_(size) {}
    template <class T>
    bool pod(T* v) {
        if (size_ - offset_ < sizeof(T)) return false;
        std::memcpy(v, data_ + offset_, sizeof(T));
        offset_ += sizeof(T);
        return true;
    }
    bool text(std::string* s) {
        uint64_t n = 0;
        if (!pod(&n) || n > size_ - offset_) return false;
        s->assign(data_ + offset_, n);
        offset_ += n;
        return true;
    }
    template <class T>
    bool array(std::vector<T>* v) {
        uint64_t n = 0;
        if (!pod(&n) || n > (size_ - offset_) / sizeof(T)) return false;
        v->resize(n);
        if (n > 0) std::memcpy(v->data(), data_ + offset_, n * sizeof(T));  // an empty vector's data() may be null
        offset_ += n * sizeof(T);
        return true;
    }
    bool atEnd() const { return offset_ == size_; }

private:
    const char* data_;
    size_t size_;
    size_t offset_ = 0;
};

std::string serialise(const ExemplarDatabase& db) {
    Writer w;
    w.pod(db.input_digest);
    w.pod(db.meters_per_pixel);
    w.pod<uint32_t>(static_cast<uint32_t>(db.exemplars.size()));
    for (size_t e = 0; e < db.exemplars.size(); ++e) {
        const ExemplarInfo& info = db.exemplars[e];
        for (const std::string* s : {&info.name, &info.path, &info.terrain_class, &info.source, &info.license}) w.text(*s);
        w.pod<int32_t>(db.exemplar_type[e]);
    }
    w.pod<uint32_t>(static_cast<uint32_t>(db.type_names.size()));
    for (const std::string& t : db.type_names) w.text(t);
    w.pod<uint32_t>(static_cast<uint32_t>(db.levels.size()));
    for (const DatabaseLevel& l : db.levels) {
        w.pod<int32_t>(l.width);
        w.pod<int32_t>(l.height);
        for (int m = 0; m < 4; ++m) w.pod(l.appearance_offset[m]);
        for (int m = 0; m < 4; ++m) w.pod(l.appearance_scale[m]);
        w.array(l.rects);
        w.array(l.height_m);
        w.array(l.appearance);
        w.array(l.similar);
        w.array(l.type);
        w.array(l.exemplar);
        w.array(l.closed);
        w.pod<uint32_t>(static_cast<uint32_t>(l.type_seeds.size()));
        for (const auto& s : l.type_seeds) w.array(s);
    }
    return std::move(w.bytes());
}

// Every invariant the synthesis kernels rely on, so a file that parses (a valid checksum proves
// nothing about who wrote it) cannot drive either backend out of bounds. The kernels only ever hold
// coordinates inside an exemplar's interior (kInteriorMargin from its edges) and read one pixel
// around them, so: every rectangle is empty or at least 5x5 and inside the atlas; the pixels inside
// rectangle e say exemplar e and carry a known type or kNoType (a void); the PatchMatch match of
// such a pixel and every seed coordinate lie in some exemplar's interior on a pixel of known type;
// an exemplar present at a level is present at every finer one (upsampling maps its pixels there);
// appearance scales are finite and positive.
Status checkLevel(const ExemplarDatabase& db, size_t index) {
    const DatabaseLevel& l = db.levels[index];
    const std::string where = "level " + std::to_string(index) + ": ";
    if (l.width <= 0 || l.height <= 0 || l.pixelCount() > limits::kMaxImagePixels)
        return Status::error(where + "atlas size " + std::to_string(l.width) + "x" + std::to_string(l.height) + " out of range");
    const size_t n = l.pixelCount();
    if (l.height_m.size() != n || l.appearance.size() != 4 * n || l.similar.size() != n || l.type.size() != n ||
        l.exemplar.size() != n || l.closed.size() != n || l.rects.size() != db.exemplars.size())
        return Status::error(where + "arrays do not match the atlas size");
    for (int m = 0; m < 4; ++m)
        if (!std::isfinite(l.appearance_offset[m]) || !(l.appearance_scale[m] >= 1e-30f && l.appearance_scale[m] <= 1e6f))
            return Status::error(where + "appearance mode " + std::to_string(m) + " has a scale or offset out of range");
    for (float h : l.height_m)
        if (!(std::fabs(h) <= 1e5f)) return Status::error(where + "a height is not finite or beyond 100 km");
    constexpr int kMinimumSide = 2 * kInteriorMargin + 1;
    auto interior = [&](uint32_t q) {
        const uint8_t e = l.exemplar[q];
        if (e == kNoExemplar || e >= l.rects.size()) return false;
        const AtlasRect& r = l.rects[e];
        const int x = static_cast<int>(q % static_cast<uint32_t>(l.width)), y = static_cast<int>(q / static_cast<uint32_t>(l.width));
        return x >= r.x + kInteriorMargin && y >= r.y + kInteriorMargin && x < r.x + r.width - kInteriorMargin &&
               y < r.y + r.height - kInteriorMargin && l.type[q] < db.type_names.size();
    };
    // Rectangles first (their bounds are what the pixel checks below rely on), then which pixels
    // name which exemplar, then what the pixels inside each rectangle hold.
    for (size_t e = 0; e < l.rects.size(); ++e) {
        const AtlasRect& r = l.rects[e];
        const bool empty = r.width == 0 && r.height == 0;
        if (r.x < 0 || r.y < 0 || (!empty && (r.width < kMinimumSide || r.height < kMinimumSide)) ||
            int64_t(r.x) + r.width > l.width || int64_t(r.y) + r.height > l.height)
            return Status::error(where + "exemplar " + std::to_string(e) + " rectangle is outside the atlas or smaller than " +
                                 std::to_string(kMinimumSide) + "x" + std::to_string(kMinimumSide));
        const bool coarser_has_it = index + 1 < db.levels.size() && db.levels[index + 1].rects.size() > e &&
                                    db.levels[index + 1].rects[e].width > 0;
        if (empty && coarser_has_it)
            return Status::error(where + "exemplar " + std::to_string(e) + " is missing below a level that has it");
    }
    for (size_t p = 0; p < n; ++p)
        if (l.exemplar[p] != kNoExemplar && (l.exemplar[p] >= l.rects.size() || l.rects[l.exemplar[p]].width == 0))
            return Status::error(where + "a pixel names a missing exemplar");
    for (uint32_t q : l.similar)
        if (q >= n) return Status::error(where + "similarity index out of range");
    for (size_t e = 0; e < l.rects.size(); ++e) {
        const AtlasRect& r = l.rects[e];
        for (int y = r.y; y < r.y + r.height; ++y)
            for (int x = r.x; x < r.x + r.width; ++x) {
                const size_t p = static_cast<size_t>(y) * l.width + x;
                if (l.exemplar[p] != e || (l.type[p] >= db.type_names.size() && l.type[p] != kNoType))
                    return Status::error(where + "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                         ") inside exemplar " + std::to_string(e) + " names another exemplar or an unknown type");
                if (!interior(l.similar[p]))
                    return Status::error(where + "the similarity table points outside the exemplars at (" + std::to_string(x) +
                                         ", " + std::to_string(y) + ")");
            }
    }
    if (l.type_seeds.size() > db.type_names.size()) return Status::error(where + "more seed lists than types");
    size_t seeds = 0;
    for (const auto& list : l.type_seeds) {
        for (uint32_t q : list)
            if (q >= n || !interior(q)) return Status::error(where + "a type seed lies outside the exemplars");
        seeds += list.size();
    }
    if (seeds == 0) return Status::error(where + "no seed coordinates");
    return Status::ok();
}

Status checkConsistency(const ExemplarDatabase& db) {
    if (db.levels.empty()) return Status::error("no pyramid levels");
    if (!(db.meters_per_pixel > 0.0 && db.meters_per_pixel <= 1e5)) return Status::error("meters_per_pixel out of range");
    if (db.exemplars.empty() || db.type_names.empty()) return Status::error("no exemplars or no terrain types");
    if (db.exemplar_type.size() != db.exemplars.size()) return Status::error("exemplar table mismatch");
    for (int t : db.exemplar_type)
        if (t < 0 || t >= static_cast<int>(db.type_names.size())) return Status::error("exemplar type out of range");
    for (size_t i = 0; i < db.levels.size(); ++i)
        if (Status s = checkLevel(db, i); !s) return s;
    return Status::ok();
}

}  // namespace

Status saveDatabase(const ExemplarDatabase& db, const std::string& path) {
    const std::string payload = serialise(db);
    std::string file(kMagic, 8);
    const uint32_t version = ExemplarDatabase::kFormatVersion, reserved = 0;
    const uint64_t size = payload.size(), checksum = fnv1a(payload.data(), payload.size());
    file.append(reinterpret_cast<const char*>(&version), 4);
    file.append(reinterpret_cast<const char*>(&reserved), 4);
    file.append(reinterpret_cast<const char*>(&size), 8);
    file.append(reinterpret_cast<const char*>(&checksum), 8);
    file += payload;
    return writeFileAtomically(path, file);
}

Result<std::shared_ptr<const ExemplarDatabase>> loadDatabase(const std::string& path) {
    auto bytes = readFileBytes(path);
    if (!bytes) return bytes.status();
    const std::string& file = bytes.value();
    if (file.size() < kHeaderBytes || std::memcmp(file.data(), kMagic, 8) != 0)
        return Status::error(path + ": not a terrasynth database (bad magic)");
    uint32_t version = 0;
    uint64_t size = 0, checksum = 0;
    std::memcpy(&version, file.data() + 8, 4);
    std::memcpy(&size, file.data() + 16, 8);
    std::memcpy(&checksum, file.data() + 24, 8);
    if (version != ExemplarDatabase::kFormatVersion)
        return Status::error(path + ": database format version " + std::to_string(version) + ", this build reads " +
                             std::to_string(ExemplarDatabase::kFormatVersion));
    if (file.size() - kHeaderBytes != size)
        return Status::error(path + ": truncated or padded (" + std::to_string(file.size() - kHeaderBytes) +
                             " payload bytes, header says " + std::to_string(size) + ")");
    const char* payload = file.data() + kHeaderBytes;
    if (fnv1a(payload, size) != checksum) return Status::error(path + ": checksum mismatch (corrupt file)");

    auto db = std::make_shared<ExemplarDatabase>();
    Reader r(payload, size);
    uint32_t exemplars = 0, types = 0, levels = 0;
    bool ok = r.pod(&db->input_digest) && r.pod(&db->meters_per_pixel) && r.pod(&exemplars) &&
              exemplars <= static_cast<uint32_t>(kMaxExemplars);
    for (uint32_t e = 0; ok && e < exemplars; ++e) {
        ExemplarInfo info;
        int32_t type = 0;
        ok = r.text(&info.name) && r.text(&info.path) && r.text(&info.terrain_class) && r.text(&info.source) &&
             r.text(&info.license) && r.pod(&type);
        db->exemplars.push_back(info);
        db->exemplar_type.push_back(type);
    }
    ok = ok && r.pod(&types) && types <= static_cast<uint32_t>(kMaxTypes);
    for (uint32_t t = 0; ok && t < types; ++t) {
        std::string name;
        ok = r.text(&name);
        db->type_names.push_back(name);
    }
    ok = ok && r.pod(&levels) && levels <= 16;
    for (uint32_t i = 0; ok && i < levels; ++i) {
        DatabaseLevel l;
        uint32_t seed_lists = 0;
        ok = r.pod(&l.width) && r.pod(&l.height);
        for (int m = 0; ok && m < 4; ++m) ok = r.pod(&l.appearance_offset[m]);
        for (int m = 0; ok && m < 4; ++m) ok = r.pod(&l.appearance_scale[m]);
        ok = ok && r.array(&l.rects) && r.array(&l.height_m) && r.array(&l.appearance) && r.array(&l.similar) &&
             r.array(&l.type) && r.array(&l.exemplar) && r.array(&l.closed) && r.pod(&seed_lists) && seed_lists <= 256;
        l.type_seeds.resize(ok ? seed_lists : 0);
        for (uint32_t s = 0; ok && s < seed_lists; ++s) ok = r.array(&l.type_seeds[s]);
        db->levels.push_back(std::move(l));
    }
    if (!ok || !r.atEnd()) return Status::error(path + ": malformed database payload");
    Status consistent = checkConsistency(*db);
    if (!consistent) return consistent.withContext(path);
    return std::shared_ptr<const ExemplarDatabase>(std::move(db));
}

Result<uint64_t> digestInputs(const std::vector<std::string>& inputs, const DatabaseBuildOptions& options) {
    // The builder revision changes whenever the algorithm builds different tables from the same
    // inputs (e.g. a better PatchMatch), so caches built by older code are rebuilt, not reused.
    constexpr uint32_t kBuilderRevision = 2;
    uint64_t h = fnv1a(reinterpret_cast<const char*>(&ExemplarDatabase::kFormatVersion), 4);
    h = fnv1a(reinterpret_cast<const char*>(&kBuilderRevision), 4, h);
    const double shape[3] = {static_cast<double>(options.levels), options.meters_per_pixel,
                             static_cast<double>(options.patchmatch_iterations)};
    h = fnv1a(reinterpret_cast<const char*>(shape), sizeof(shape), h);
    for (const std::string& input : inputs) {
        std::vector<std::string> files;
        if (::access((input + "/.").c_str(), F_OK) == 0) {
            auto listed = listExemplarFiles(input);
            if (!listed) return listed.status();
            files = listed.value();
        } else {
            files.push_back(input);
        }
        for (const std::string& f : files) {
            for (const std::string& part : {f, f.substr(0, f.find_last_of('.')) + ".json"}) {
                auto bytes = readFileBytes(part);
                if (!bytes) {
                    if (part == f) return bytes.status();
                    continue;  // sidecars are optional for some formats
                }
                h = fnv1a(bytes->data(), bytes->size(), h);
            }
        }
    }
    return h;
}

Result<std::shared_ptr<const ExemplarDatabase>> loadOrBuildDatabase(const std::vector<std::string>& inputs,
                                                                    const DatabaseBuildOptions& options,
                                                                    const std::string& cache_path, bool* rebuilt,
                                                                    std::string* why) {
    auto digest = digestInputs(inputs, options);
    if (!digest) return digest.status();
    std::string reason;
    if (::access(cache_path.c_str(), F_OK) != 0) {
        reason = cache_path + ": no cache yet";
    } else {
        auto cached = loadDatabase(cache_path);
        if (cached && cached.value()->input_digest == digest.value()) {
            if (rebuilt) *rebuilt = false;
            return cached;
        }
        reason = cached ? cache_path + ": stale (inputs or options changed)" : cached.message();
    }
    if (rebuilt) *rebuilt = true;
    if (why) *why = reason;
    auto built = buildDatabase(inputs, options);
    if (!built) return built;
    Status saved = saveDatabase(*built.value(), cache_path);
    if (!saved) return saved;
    return built;
}

}  // namespace terrasynth
