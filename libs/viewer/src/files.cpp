#include "fresnel/viewer/files.h"

#include "fresnel/core/atomic_file.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>

namespace fresnel::viewer {
namespace fs = std::filesystem;

std::string lower_extension(const fs::path& p) {
    std::string e = p.extension().string();
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

bool is_model(const fs::path& p) {
    auto e = lower_extension(p);
    return e == ".gltf" || e == ".glb" || e == ".obj" || p.filename().string().ends_with(".fresnel.json");
}

bool is_gltf(const fs::path& p) {
    auto e = lower_extension(p);
    return e == ".gltf" || e == ".glb";
}

bool is_environment(const fs::path& p) {
    auto e = lower_extension(p);
    std::error_code ec;
    return e == ".hdr" || e == ".exr" || e == ".ktx2" || (fs::is_directory(p, ec) && fs::exists(p / "manifest.json", ec));
}

bool is_folder(const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(p, ec);
}

fs::path image_beside(const fs::path& scene) {
    std::string name = scene.filename().string();
    for (const char* suffix : {".json", ".fresnel"})
        if (name.size() > std::strlen(suffix) && name.ends_with(suffix)) name.resize(name.size() - std::strlen(suffix));
    return scene.parent_path() / (name + ".png");
}

std::vector<std::string> list_models(const fs::path& folder) {
    std::vector<std::string> out;
    std::error_code ec;
    fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
        if (it.depth() > 3) it.disable_recursion_pending();
        if (it->is_regular_file(ec) && is_model(it->path()))
            out.push_back(fs::absolute(it->path()).lexically_normal().string());
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::string> sibling_models(const std::string& model) {
    fs::path folder = fs::absolute(model).parent_path();
    std::vector<std::string> models = list_models(folder);
    for (int up = 0; up < 2 && models.size() <= 1 && folder.has_parent_path() && folder != folder.root_path(); ++up) {
        folder = folder.parent_path();
        models = list_models(folder);
    }
    return models;
}

std::optional<std::string> step_folder(const std::vector<std::string>& models, const std::string& opened, int delta) {
    if (models.empty()) return std::nullopt;
    const std::string current = opened.empty() ? std::string() : fs::absolute(opened).lexically_normal().string();
    auto it = std::find(models.begin(), models.end(), current);
    long i = it == models.end() ? 0 : long(it - models.begin()) + delta;
    const long n = long(models.size());
    i = ((i % n) + n) % n;
    return models[std::size_t(i)];
}

void RecentFiles::load(const fs::path& file) {
    std::ifstream in(file);
    for (std::string line; paths_.size() < kCapacity && std::getline(in, line);)
        if (!line.empty()) paths_.push_back(line);
}

void RecentFiles::add(const std::string& path) {
    std::string p = fs::absolute(path).lexically_normal().string();
    paths_.erase(std::remove(paths_.begin(), paths_.end(), p), paths_.end());
    paths_.insert(paths_.begin(), p);
    if (paths_.size() > kCapacity) paths_.resize(kCapacity);
}

bool RecentFiles::save(const fs::path& file) const {
    std::error_code ec;
    if (file.has_parent_path()) fs::create_directories(file.parent_path(), ec);
    std::string text;
    for (const auto& p : paths_) text += p + "\n";
    try {
        write_file_atomically(file, text);  // whole or absent, as every writer (fresnel/core/atomic_file.h)
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace fresnel::viewer
