#include "terrain_loader.h"

namespace terrasynth::game {

TerrainLoader::TerrainLoader(Project project, TerrainOptions options, std::function<void(Terrain&)> after_open) {
    options.database.progress = [this](const std::string& stage, double p) {
        std::lock_guard<std::mutex> lock(mutex_);
        stage_ = "building the exemplar database: " + stage;
        progress_ = p;
    };
    thread_ = std::thread([this, project = std::move(project), options = std::move(options),
                           after_open = std::move(after_open)]() mutable {
        auto opened = Terrain::fromProject(std::move(project), options);
        if (opened && after_open) {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                stage_ = "synthesizing the first view";
                progress_ = 1.0;
            }
            after_open(**opened);
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            result_ = std::move(opened);
        }
        done_ = true;
    });
}

TerrainLoader::~TerrainLoader() { thread_.join(); }

std::string TerrainLoader::stage() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stage_;
}

double TerrainLoader::progress() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return progress_;
}

Result<std::shared_ptr<Terrain>> TerrainLoader::result() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return result_;
}

}  // namespace terrasynth::game
