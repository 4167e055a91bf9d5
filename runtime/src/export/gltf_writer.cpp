// Writing the model: tinygltf serialises the JSON (buffer left empty), the binary blocks are streamed
// straight to disk so a 1 GB export is never copied whole in memory.
#include <tiny_gltf.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/paths.h"
#include "export/export_internal.h"

namespace terrasynth::export_detail {

namespace {

// A file written under a temporary name and renamed into place on commit().
class AtomicFile {
public:
    explicit AtomicFile(std::string path)
        : path_(std::move(path)), temp_(path_ + ".tmp." + std::to_string(::getpid())) {
        out_.open(temp_, std::ios::binary | std::ios::trunc);
    }
    ~AtomicFile() {
        if (!committed_) {
            out_.close();
            std::remove(temp_.c_str());
        }
    }
    bool isOpen() const { return out_.is_open(); }
    void write(const void* data, size_t size) { out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(size)); }
    void zeros(size_t n) {
        static const char kZeros[4] = {0, 0, 0, 0};
        write(kZeros, n);
    }
    Status commit() {
        out_.close();
        if (out_.fail()) return Status::error(path_ + ": write failed (disk full?)");
        if (std::rename(temp_.c_str(), path_.c_str()) != 0) return Status::error(path_ + ": cannot rename the temporary file into place");
        committed_ = true;
        return Status::ok();
    }

private:
    std::string path_, temp_;
    std::ofstream out_;
    bool committed_ = false;
};

void writeBlocks(AtomicFile& file, const BinaryLayout& layout) {
    size_t at = 0;
    for (const BinaryLayout::Block& block : layout.blocks) {
        file.zeros(block.offset - at);
        file.write(block.data, block.size);
        at = block.offset + block.size;
    }
    file.zeros(layout.total_bytes - at);
}

void writeLe32(AtomicFile& file, uint32_t v) {
    const uint8_t bytes[4] = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
    file.write(bytes, 4);
}

}  // namespace

Status writeGltfFiles(const std::string& path, tinygltf::Model& model, const BinaryLayout& layout,
                      size_t* json_bytes, size_t* file_bytes) {
    if (!isGltfPath(path)) return Status::error(path + ": the output must end in .glb or .gltf");
    const bool binary = detail::hasExtension(path, ".glb");
    tinygltf::TinyGLTF writer;
    std::ostringstream stream;
    if (!writer.WriteGltfSceneToStream(&model, stream, /*prettyPrint=*/false, /*writeBinary=*/false))
        return Status::error(path + ": tinygltf could not serialise the model");
    // tinygltf writes the (empty) buffer as a data URI; describe the real one instead.
    nlohmann::json json = nlohmann::json::parse(stream.str(), nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded()) return Status::error(path + ": tinygltf produced invalid JSON");
    const size_t padded_bin = (layout.total_bytes + 3) & ~size_t(3);
    nlohmann::json buffer = {{"byteLength", layout.total_bytes}};
    std::string bin_path;
    if (!binary) {
        bin_path = detail::replaceExtension(path, ".bin");
        buffer["uri"] = detail::baseName(bin_path);
    }
    json["buffers"] = nlohmann::json::array({buffer});
    std::string text = json.dump();
    *json_bytes = text.size();

    if (binary) {
        text.append((4 - text.size() % 4) % 4, ' ');  // the JSON chunk is padded with spaces
        AtomicFile file(path);
        if (!file.isOpen()) return Status::error(path + ": cannot create the file");
        const size_t total = 12 + 8 + text.size() + (layout.total_bytes ? 8 + padded_bin : 0);
        if (total > 0xFFFFFFFFull) return Status::error(path + ": over 4 GiB, the GLB limit; export a smaller region or use quantization");
        writeLe32(file, 0x46546C67u);  // "glTF"
        writeLe32(file, 2);
        writeLe32(file, static_cast<uint32_t>(total));
        writeLe32(file, static_cast<uint32_t>(text.size()));
        writeLe32(file, 0x4E4F534Au);  // "JSON"
        file.write(text.data(), text.size());
        if (layout.total_bytes) {
            writeLe32(file, static_cast<uint32_t>(padded_bin));
            writeLe32(file, 0x004E4942u);  // "BIN\0"
            writeBlocks(file, layout);
            file.zeros(padded_bin - layout.total_bytes);
        }
        *file_bytes = total;
        return file.commit();
    }
    AtomicFile bin(bin_path);
    if (!bin.isOpen()) return Status::error(bin_path + ": cannot create the file");
    writeBlocks(bin, layout);
    if (Status s = bin.commit(); !s) return s;
    AtomicFile file(path);
    if (!file.isOpen()) return Status::error(path + ": cannot create the file");
    file.write(text.data(), text.size());
    *file_bytes = text.size() + layout.total_bytes;
    return file.commit();
}

}  // namespace terrasynth::export_detail
