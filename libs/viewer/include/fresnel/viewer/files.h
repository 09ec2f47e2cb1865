#pragma once
// What the viewer opens and steps through, without a window: which paths are models, scene
// files and environments, the models of a folder (PageUp/PageDown), and the recent-files list.
// The panels, the drop handler and the script's `open` call these.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fresnel::viewer {

// The extension in lower case, with its dot (".glb"); empty when there is none.
std::string lower_extension(const std::filesystem::path& p);
// What `open` takes as a scene: a model the loaders read (.gltf, .glb, .obj) or a scene file
// (*.fresnel.json; other .json files are not listed, but open as scene files when named).
bool is_model(const std::filesystem::path& p);
bool is_gltf(const std::filesystem::path& p);
// An environment: an .hdr or .exr panorama, or a baked folder (one holding manifest.json).
// Never throws: an unreadable entry is not an environment.
bool is_environment(const std::filesystem::path& p);
bool is_folder(const std::filesystem::path& p);
// The image beside a scene file that `fresnel render SCENE` writes: shot.fresnel.json -> shot.png.
std::filesystem::path image_beside(const std::filesystem::path& scene);

// The models under `folder`, three levels deep: absolute, normal paths, sorted.
std::vector<std::string> list_models(const std::filesystem::path& folder);
// The models PageUp/PageDown step through from `model`: those under its folder, or under the
// folder above when the model is alone in its own (models/NAME/NAME.glb,
// models/NAME/glTF-Binary/NAME.glb), up to two levels.
std::vector<std::string> sibling_models(const std::string& model);
// The model `delta` steps from `opened` (any spelling of the path) in `models`, wrapping
// around at both ends; the first model when `opened` is not among them; nothing when
// `models` is empty.
std::optional<std::string> step_folder(const std::vector<std::string>& models, const std::string& opened, int delta);

// The files opened last, newest first: at most kCapacity, each once, as absolute normal paths.
// Where the list is kept is the caller's (the viewer: viewer-recent.txt in the cache folder).
class RecentFiles {
public:
    static constexpr std::size_t kCapacity = 12;
    // Appends the paths of `file` (one a line, blank lines skipped) up to kCapacity; a
    // missing or unreadable file adds nothing.
    void load(const std::filesystem::path& file);
    // `path` at the front, an earlier entry of it removed, the oldest beyond kCapacity dropped.
    void add(const std::string& path);
    // Writes the list to `file`, one path a line, creating its folder. Best effort: false
    // when it could not be written (the list is a convenience, never an error).
    bool save(const std::filesystem::path& file) const;
    const std::vector<std::string>& paths() const { return paths_; }

private:
    std::vector<std::string> paths_;
};

}  // namespace fresnel::viewer
