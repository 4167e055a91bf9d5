// Writing the model: tinygltf serialises the JSON (buffer left empty), the binary blocks are streamed
// straight to disk so a 1 GB export is never copied whole in memory.
#include <tiny_gltf.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/json_reader.h"
#include "core/paths.h"
#include "export/export_internal.h"

namespace terrasynth::export_detail {

namespace {

// A temporary file being streamed; remembers the first failed write so one check at the end covers
// all of them (a full disk fails late, inside a buffered write).
class StreamedFile {
public:
    explicit StreamedFile(const std::string& temp)
        : file_(std::fopen(temp.c_str(), "wb")), open_error_(file_ ? 0 : errno) {}
    ~StreamedFile() {
        if (file_) std::fclose(file_);
    }
    StreamedFile(const StreamedFile&) = delete;
    StreamedFile& operator=(const StreamedFile&) = delete;
    bool isOpen() const { return file_ != nullptr; }
    std::string openError() const { return std::strerror(open_error_); }
    void write(const void* data, size_t size) {
        if (ok_ && size > 0) ok_ = std::fwrite(data, 1, size, file_) == size;
    }
    void zeros(size_t n) {
        static const char kZeros[4] = {0, 0, 0, 0};
        write(kZeros, n);
    }
    // Closes the file; the status names `path`, the file it will become.
    Status finish(const std::string& path) {
        const bool closed = std::fclose(file_) == 0;
        file_ = nullptr;
        if (!ok_ || !closed) return Status::error(path + ": write failed (disk full?)");
        return Status::ok();
    }

private:
    std::FILE* file_;
    int open_error_;
    bool ok_ = true;
};

void writeBlocks(StreamedFile& file, const BinaryLayout& layout) {
    size_t at = 0;
    for (const BinaryLayout::Block& block : layout.blocks) {
        file.zeros(block.offset - at);
        file.write(block.data, block.size);
        at = block.offset + block.size;
    }
    file.zeros(layout.total_bytes - at);
}

void writeLe32(StreamedFile& file, uint32_t v) {
    const uint8_t bytes[4] = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
    file.write(bytes, 4);
}

// Stages `path` written by `body` into a streamed temporary.
Status stageStreamed(FileTransaction& transaction, const std::string& path,
                     const std::function<void(StreamedFile&)>& body) {
    return transaction.stageWith(path, [&](const std::string& temp) {
        StreamedFile file(temp);
        if (!file.isOpen()) return Status::error(path + ": cannot create a temporary file beside it: " + file.openError());
        body(file);
        return file.finish(path);
    });
}

}  // namespace

Status stageGltfFiles(FileTransaction& transaction, const std::string& path, tinygltf::Model& model,
                      const BinaryLayout& layout, size_t* json_bytes, size_t* file_bytes) {
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
    std::string text = detail::dumpJson(json);
    *json_bytes = text.size();

    if (binary) {
        text.append((4 - text.size() % 4) % 4, ' ');  // the JSON chunk is padded with spaces
        const size_t total = 12 + 8 + text.size() + (layout.total_bytes ? 8 + padded_bin : 0);
        if (total > 0xFFFFFFFFull) return Status::error(path + ": over 4 GiB, the GLB limit; export a smaller region or use quantization");
        *file_bytes = total;
        return stageStreamed(transaction, path, [&](StreamedFile& file) {
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
        });
    }
    // The .gltf names the .bin, so it is staged last.
    if (Status s = stageStreamed(transaction, bin_path, [&](StreamedFile& file) { writeBlocks(file, layout); }); !s)
        return s;
    *file_bytes = text.size() + layout.total_bytes;
    return transaction.stage(path, text);
}

}  // namespace terrasynth::export_detail
