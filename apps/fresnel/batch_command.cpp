// `fresnel batch JOBS [--shard I/N|auto] [--jobs K] [--out DIR] [--json] [--resume]`: many
// render jobs in one process. JOBS is a JSON Lines file (one job per line: a scene file, a
// model, or an object with a model and the scene-file keys inline; docs/batch.md) or a folder
// of models (a thumbnail each). render's flags are every job's defaults.
//
// Why one process: a `fresnel render` pays for EGL start-up, shader compilation, the
// environment's load (or bake) and its upload in every image. Here each worker keeps its GL
// context and renderer (programs compiled once, the environment uploaded once: the renderer
// keys it by BakedIbl::content_hash), and the workers share the loaded environments and the
// last models. A job that fails is reported and the batch goes on; the exit code says whether
// any failed. Outputs are whole or absent (fresnel/core/atomic_file.h), and each is recorded,
// with its size and checksum, in a log in --out once it is in place (batch_outputs.h): --resume
// skips an output only when the log vouches for it as it is on the disk.
// Long (~760 lines): the job list reader, the sharding, the workers and the report are one
// command's parts, kept in one file as every other command is.
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/core/process_memory.h"
#include "fresnel/gpu/context.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/job/job.h"
#include "fresnel/render/renderer.h"
#include "fresnel/trace/job_inputs.h"
#include "fresnel/job/scene_document.h"
#include "fresnel/job/settings.h"
#include "fresnel/scene/paths.h"
#include "command_line.h"
#include "job_options.h"
#include "batch_outputs.h"
#include "fresnel/core/atomic_file.h"

namespace fresnel::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr std::size_t kMaxJobs = 10'000'000;  // a job list longer than this is refused

struct BatchOptions {
    std::string jobs;
    std::string shard;
    int shard_count = 0;
    int workers = 1;
    std::string out = ".";
    std::string format = "png";
    bool resume = false;
    std::size_t cache_models = 2;
    RenderOptions render;
};

// One job of the list, before it is read: what to read, where its output goes.
struct BatchJob {
    std::size_t index = 0;  // in the whole list (the shard takes index % N == I)
    std::string label;      // "jobs.jsonl:3", "jobs.jsonl:3 #5" (sweep frame), a model's path
    std::string model;      // folder mode: the model
    std::string scene_path; // a scene file to read (then `doc` is a merge patch onto it)
    std::shared_ptr<const json> doc;  // the inline job (or patch), shared by a sweep's frames; null when none
    fs::path base;          // relative paths of `doc` resolve here
    std::vector<std::pair<std::string, double>> sweep;  // JSON pointer, value
    std::string output;     // relative to --out
    std::string error;      // set: the line was broken; reported, not rendered
};

std::string stem_of(const std::string& path) {
    std::string s = fs::path(path).stem().string();
    if (s.size() > 8 && s.compare(s.size() - 8, 8, ".fresnel") == 0) s.resize(s.size() - 8);
    return s.empty() ? std::string("job") : s;
}

// A sweep parameter: a setting sweeps offer (fresnel/job/settings.h; its key "camera.yaw" or its
// flag's name "yaw") as the scene-file pointer it sets, or a JSON pointer as given; "" when unknown.
const settings::Setting* sweep_setting(const std::string& name) {
    const settings::Setting* s = settings::find(name);
    return s && s->offered(settings::kSweep) ? s : nullptr;
}
std::string sweep_pointer(const std::string& name) {
    if (!name.empty() && name[0] == '/') return name;
    const settings::Setting* s = sweep_setting(name);
    if (!s) return {};
    std::string ptr = "/" + s->key;
    std::replace(ptr.begin(), ptr.end(), '.', '/');
    return ptr;
}
std::string sweep_names() {
    std::string names;
    for (const settings::Setting* s : settings::offered_by(settings::kSweep)) names += s->flag.substr(2) + ", ";
    return names;
}

// "sweep": {"NAME": [start, stop, count] | {"values": [...]}, ...}: the frames, every
// combination of the parameters (the first varies slowest). An angle's full turn leaves out
// the stop (it is the start again): [0, 360, 24] is 0, 15, ..., 345.
std::vector<std::vector<std::pair<std::string, double>>> expand_sweep(const json& sweep) {
    if (!sweep.is_object() || sweep.empty()) throw std::runtime_error("/sweep: must be an object of parameters");
    std::vector<std::vector<std::pair<std::string, double>>> frames(1);
    for (auto it = sweep.begin(); it != sweep.end(); ++it) {
        std::string ptr = sweep_pointer(it.key());
        if (ptr.empty())
            throw std::runtime_error("/sweep/" + it.key() + ": unknown parameter (" + sweep_names() +
                                     "their keys such as camera.yaw, or a JSON pointer such as /camera/yaw)");
        std::vector<double> values;
        const json& v = it.value();
        auto num = [&](const json& x) {
            if (!x.is_number() || !std::isfinite(x.get<double>()))
                throw std::runtime_error("/sweep/" + it.key() + ": values must be finite numbers");
            return x.get<double>();
        };
        if (v.is_array() && v.size() == 3) {
            double a = num(v[0]), b = num(v[1]), n = num(v[2]);
            if (n < 1 || n > 100000 || n != std::floor(n))
                throw std::runtime_error("/sweep/" + it.key() + ": the count (third value) must be an integer 1..100000");
            const settings::Setting* setting = sweep_setting(it.key());
            bool angle = setting ? setting->periodic : ptr == "/camera/yaw" || ptr == "/environment/rotation";
            bool turn = angle && std::fabs(b - a) > 0 && std::fmod(std::fabs(b - a), 360.0) == 0.0;
            int count = int(n);
            for (int i = 0; i < count; ++i)
                values.push_back(count == 1 ? a : turn ? a + (b - a) * i / count : a + (b - a) * i / (count - 1));
        } else if (v.is_object() && v.contains("values") && v["values"].is_array() && !v["values"].empty() &&
                   v.size() == 1) {
            for (const auto& x : v["values"]) values.push_back(num(x));
        } else {
            throw std::runtime_error("/sweep/" + it.key() + ": must be [start, stop, count] or {\"values\": [...]}");
        }
        std::vector<std::vector<std::pair<std::string, double>>> next;
        for (const auto& f : frames)
            for (double x : values) {
                auto g = f;
                g.emplace_back(ptr, x);
                next.push_back(std::move(g));
                if (next.size() > 100000) throw std::runtime_error("/sweep: more than 100000 frames");
            }
        frames = std::move(next);
    }
    return frames;
}

// What folder mode renders: every format the loaders read, and scene files (*.fresnel.json;
// other .json files in a folder of models are not jobs).
bool is_folder_scene_file(const fs::path& p) { return p.filename().string().ends_with(".fresnel.json"); }
bool is_model_file(const fs::path& p) {
    std::string e = lower_extension(p.string());
    return e == ".gltf" || e == ".glb" || e == ".obj" || is_folder_scene_file(p);
}

// The whole job list (every shard reads the same list, so indices and names agree).
// `ignores_case`: --out's file system folds case (two names differing in case are one file).
std::vector<BatchJob> read_job_list(const BatchOptions& o, bool ignores_case) {
    std::vector<BatchJob> jobs;
    const fs::path src(o.jobs);
    std::error_code ec;
    const std::string ext = "." + o.format;
    if (fs::is_directory(src, ec)) {
        // Thumbnail mode: every model under the folder, sorted, each named by its relative path.
        std::vector<fs::path> models;
        for (auto it = fs::recursive_directory_iterator(src, fs::directory_options::skip_permission_denied, ec);
             it != fs::recursive_directory_iterator(); it.increment(ec)) {
            if (ec) break;
            if (it->is_regular_file(ec) && is_model_file(it->path())) models.push_back(it->path());
        }
        std::sort(models.begin(), models.end());
        for (const auto& m : models) {
            BatchJob j;
            if (is_folder_scene_file(m)) j.scene_path = m.string();  // read as a scene-file job line
            else j.model = m.string();
            fs::path rel = fs::relative(m, src, ec);
            j.label = rel.string();
            j.output = (rel.parent_path() / (stem_of(rel.string()) + ext)).string();  // shot.fresnel.json -> shot.png
            jobs.push_back(std::move(j));
        }
    } else {
        std::ifstream in(src, std::ios::binary);
        if (!in) throw Error(o.jobs, "", "cannot open the job list (a .jsonl file or a folder of models)");
        const fs::path base = src.parent_path().empty() ? fs::path(".") : src.parent_path();
        SceneFileOptions limits;
        limits.max_bytes = std::size_t(1) << 20;  // per line
        std::string line;
        std::size_t line_no = 0, total_bytes = 0;
        while (std::getline(in, line)) {
            ++line_no;
            total_bytes += line.size();
            if (total_bytes > (std::size_t(1) << 30)) throw Error(o.jobs, "", "the job list is larger than 1 GiB");
            if (!line.empty() && line.back() == '\r') line.pop_back();
            std::size_t first = line.find_first_not_of(" \t");
            if (first == std::string::npos || line[first] == '#') continue;  // blank lines and # comments
            BatchJob j;
            j.label = src.filename().string() + ":" + std::to_string(line_no);
            j.base = base;
            std::string stem = "job";
            std::string explicit_output;
            std::vector<std::vector<std::pair<std::string, double>>> frames(1);
            try {
                json doc = parse_json_limited(line, j.label, limits);
                if (doc.is_string()) doc = is_scene_file(doc.get<std::string>()) ? json{{"scene", doc}} : json{{"model", doc}};
                if (!doc.is_object()) throw std::runtime_error("a job is a JSON object or a string (a scene file or model)");
                if (doc.contains("scene")) {
                    if (!doc["scene"].is_string()) throw std::runtime_error("/scene: must be a string (a scene file)");
                    std::string error;
                    auto p = resolve_relative_path(doc["scene"].get<std::string>(), base, o.render.allow_external(), error);
                    if (!p) throw std::runtime_error("/scene: " + error);
                    j.scene_path = p->string();
                    stem = stem_of(j.scene_path);
                    doc.erase("scene");
                } else if (doc.contains("model") && doc["model"].is_string()) {
                    stem = stem_of(doc["model"].get<std::string>());
                    if (doc["model"].get<std::string>() == "demo") stem = "demo";
                } else if (doc.contains("models") && doc["models"].is_array() && !doc["models"].empty() &&
                           doc["models"][0].is_object() && doc["models"][0].contains("path") &&
                           doc["models"][0]["path"].is_string()) {
                    stem = stem_of(doc["models"][0]["path"].get<std::string>());
                }
                if (doc.contains("output")) {
                    if (!doc["output"].is_string()) throw std::runtime_error("/output: must be a string");
                    explicit_output = doc["output"].get<std::string>();
                    std::string error;
                    if (!resolve_relative_path(explicit_output, fs::path("."), false, error))
                        throw std::runtime_error("/output: must be a relative path inside --out, not '" +
                                                 explicit_output.substr(0, explicit_output.find('\0')) + "'");
                    std::string e = lower_extension(explicit_output);
                    if (e != ".png" && e != ".exr" && e != ".hdr")
                        throw std::runtime_error("/output: must end in .png, .exr or .hdr");
                    doc.erase("output");
                }
                if (doc.contains("sweep")) {
                    frames = expand_sweep(doc["sweep"]);
                    doc.erase("sweep");
                }
                j.doc = std::make_shared<const json>(std::move(doc));
            } catch (const Error& e) {
                j.error = e.what();
            } catch (const std::exception& e) {
                j.error = j.label + ": " + e.what();
            }
            if (!j.error.empty()) {
                j.output = stem + "-line" + std::to_string(line_no) + ext;
                jobs.push_back(std::move(j));
                continue;
            }
            const bool sweep = frames.size() > 1 || !frames[0].empty();
            const int digits = std::max(3, int(std::to_string(frames.size() - 1).size()));
            if (jobs.size() + frames.size() > kMaxJobs)
                throw Error(o.jobs, "line " + std::to_string(line_no), "more than " + std::to_string(kMaxJobs) + " jobs");
            for (std::size_t f = 0; f < frames.size(); ++f) {
                BatchJob k = j;
                k.sweep = frames[f];
                std::string name = explicit_output.empty() ? stem + ext : explicit_output;
                if (sweep) {
                    std::string num = std::to_string(f);
                    if (num.size() < std::size_t(digits)) num.insert(0, std::size_t(digits) - num.size(), '0');
                    fs::path p(name);
                    name = (p.parent_path() / (p.stem().string() + "-" + num + p.extension().string())).string();
                    k.label += " #" + std::to_string(f);
                }
                k.output = name;
                jobs.push_back(std::move(k));
            }
        }
    }
    // Deterministic, unique names: a name taken by an earlier job gets the job's index. Names are
    // compared canonical ("./a.png", "sub/../a.png" and, where the file system folds case,
    // "A.png" are all "a.png"), so no two jobs write one file.
    std::set<std::string> taken;
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        jobs[i].index = i;
        std::string name = canonical_output_name(jobs[i].output);
        while (taken.count(output_key(name, ignores_case))) {
            fs::path p(name);
            name = (p.parent_path() / (p.stem().string() + "-" + std::to_string(i) + p.extension().string())).generic_string();
        }
        taken.insert(output_key(name, ignores_case));
        jobs[i].output = name;
    }
    return jobs;
}

// --shard I/N, or auto: Slurm array jobs (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN of
// SLURM_ARRAY_TASK_COUNT), Kubernetes Indexed Jobs (JOB_COMPLETION_INDEX of --shard-count or
// FRESNEL_SHARD_COUNT). Returns false after printing a usage error.
bool parse_shard(const BatchOptions& o, long& index, long& count) {
    index = 0;
    count = 1;
    auto env_long = [](const char* name, long& v) {
        const char* s = std::getenv(name);
        if (!s || !*s) return false;
        char* end = nullptr;
        v = std::strtol(s, &end, 10);
        return end && *end == 0;
    };
    if (o.shard.empty()) return true;
    if (o.shard == "auto") {
        long id = 0, n = 0, min = 0;
        if (env_long("SLURM_ARRAY_TASK_ID", id)) {
            env_long("SLURM_ARRAY_TASK_MIN", min);
            if (o.shard_count > 0) n = o.shard_count;
            else if (!env_long("SLURM_ARRAY_TASK_COUNT", n)) {
                print_error("--shard auto: SLURM_ARRAY_TASK_ID is set but SLURM_ARRAY_TASK_COUNT is not (or give --shard-count)");
                return false;
            }
            index = id - min;
        } else if (env_long("JOB_COMPLETION_INDEX", id)) {
            if (o.shard_count > 0) n = o.shard_count;
            else if (!env_long("FRESNEL_SHARD_COUNT", n)) {
                print_error("--shard auto: JOB_COMPLETION_INDEX is set; give the number of shards with --shard-count N or "
                            "FRESNEL_SHARD_COUNT (the Indexed Job's completions)");
                return false;
            }
            index = id;
        } else {
            std::fprintf(stderr, "fresnel: --shard auto: no SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX; rendering every job\n");
            return true;
        }
        count = n;
    } else {
        char slash = 0;
        std::stringstream ss(o.shard);
        if (!(ss >> index >> slash >> count) || slash != '/' || !ss.eof()) {
            print_error("--shard: expected I/N (0 <= I < N) or auto, got '" + o.shard + "'");
            return false;
        }
    }
    if (count < 1 || index < 0 || index >= count) {
        print_error("--shard: index " + std::to_string(index) + " is not in 0.." + std::to_string(count - 1));
        return false;
    }
    return true;
}

// Models and environments shared by the workers. Models: the last few, keyed by the job's
// source (a sweep, or jobs that differ only in light, reuse one). Environments and BRDF
// tables: by what they were baked from, so every job with the same environment shares one
// BakedIbl, which the renderers then do not upload again.
class Caches {
public:
    explicit Caches(std::size_t max_models) : max_models_(std::max<std::size_t>(max_models, 1)) {}

    std::shared_ptr<const Scene> scene(const Job& job, Diagnostics& diag, bool& loaded) {
        {
            std::lock_guard lock(mutex_);
            for (auto it = scenes_.begin(); it != scenes_.end(); ++it)
                if (it->first == job.source) {
                    scenes_.splice(scenes_.begin(), scenes_, it);
                    loaded = false;
                    return scenes_.front().second;
                }
        }
        auto scene = std::make_shared<const Scene>(load_scene(job, diag));
        loaded = true;
        std::lock_guard lock(mutex_);
        scenes_.emplace_front(job.source, scene);
        while (scenes_.size() > max_models_) scenes_.pop_back();
        return scene;
    }

    std::shared_ptr<const ibl::BakedIbl> environment(const ResolvedJob& r) {
        const std::string key = lighting_key(r);  // the job layer's one key (the viewer's and the page's)
        std::lock_guard lock(env_mutex_);  // one load or bake at a time; the others wait for it
        for (auto it = envs_.begin(); it != envs_.end(); ++it)
            if (it->first == key) {
                envs_.splice(envs_.begin(), envs_, it);
                return envs_.front().second;
            }
        auto env = std::make_shared<const ibl::BakedIbl>(ibl::load_or_bake(*r.environment, r.bake_options, {}, r.use_cache));
        envs_.emplace_front(key, env);
        while (envs_.size() > 4) envs_.pop_back();
        return env;
    }

    std::shared_ptr<const ImageF> brdf_lut(const ResolvedJob& r) {
        const std::string key = lighting_key(r);
        std::lock_guard lock(env_mutex_);
        auto& lut = luts_[key];
        if (!lut) lut = std::make_shared<const ImageF>(ibl::load_or_bake_lut(r.bake_options, r.use_cache));
        return lut;
    }

private:
    std::size_t max_models_;
    std::mutex mutex_, env_mutex_;
    std::list<std::pair<Job::Source, std::shared_ptr<const Scene>>> scenes_;
    std::list<std::pair<std::string, std::shared_ptr<const ibl::BakedIbl>>> envs_;
    std::map<std::string, std::shared_ptr<const ImageF>> luts_;  // by lighting key (a few bake options at most)
};

// Progress on stderr: a bar with the rate and the time left on a terminal, else a plain
// line per finished job (logs of cluster jobs).
class BatchProgress {
public:
    explicit BatchProgress(std::size_t total) : total_(total), tty_(isatty(STDERR_FILENO) != 0), start_(Clock::now()) {}
    void job_done(bool failed, bool skipped) {
        std::lock_guard lock(mutex_);
        ++done_;
        failed_ += failed;
        rendered_ += !failed && !skipped;
        double s = std::chrono::duration<double>(Clock::now() - start_).count();
        double rate = s > 0 ? double(rendered_) / s : 0.0;  // images per second
        double left = rate > 0 ? double(total_ - done_) / (double(done_) / s) : 0.0;
        int m = int(left) / 60, sec = int(left) % 60;
        if (tty_) {
            int filled = total_ ? int(30 * done_ / total_) : 30;
            std::fprintf(stderr, "\rbatch [%.*s%*s] %zu/%zu  %.2f images/s  %d:%02d left%s", filled,
                         "##############################", 30 - filled, "", done_, total_, rate, m, sec,
                         failed_ ? ("  " + std::to_string(failed_) + " failed").c_str() : "");
            if (done_ == total_) std::fprintf(stderr, "\n");
        } else {
            std::fprintf(stderr, "fresnel: batch: %zu/%zu done, %.2f images/s, %d:%02d left, %zu failed\n", done_, total_,
                         rate, m, sec, failed_);
        }
        std::fflush(stderr);
    }

private:
    std::size_t total_, done_ = 0, failed_ = 0, rendered_ = 0;
    bool tty_;
    Clock::time_point start_;
    std::mutex mutex_;
};

// The Job a batch entry describes, read onto `defaults` (the flags).
Job read_job(const BatchJob& b, const Job& defaults, bool allow_external, Diagnostics& diag) {
    SceneFileOptions so;
    so.allow_external_files = allow_external;
    if (!b.model.empty()) {
        Job job = defaults;
        job.source.model = b.model;
        job.source.models.clear();
        return job;
    }
    json doc = b.doc ? *b.doc : json::object();
    std::string name = b.label;
    fs::path base = b.base;
    if (!b.scene_path.empty()) {
        // The scene file, with the line's keys as a merge patch (RFC 7396) on top.
        std::ifstream in(b.scene_path, std::ios::binary);
        if (!in) throw Error(b.scene_path, "", "cannot open the scene file");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        json file = parse_json_limited(text, b.scene_path, so);
        if (!file.is_object()) throw Error(b.scene_path, "", "a scene file is a JSON object");
        if (!file.contains("fresnel")) throw Error(b.scene_path, "/fresnel", "a scene file needs \"fresnel\": 1");
        file.erase("output");  // batch outputs are named by the batch (docs/batch.md)
        if (!doc.empty()) file.merge_patch(doc);
        doc = std::move(file);
        name = b.scene_path;
        base = fs::path(b.scene_path).parent_path();
        if (base.empty()) base = ".";
    } else {
        so.require_version = false;
    }
    // A sweep sets keys of the object forms: "environment": "studio" becomes {"type": "studio"}.
    if (!b.sweep.empty() && doc.contains("environment") && doc["environment"].is_string()) {
        std::string e = doc["environment"].get<std::string>();
        json obj;
        if (e == "studio" || e == "none" || e == "automatic") {
            obj = {{"type", e}};
        } else if (e.rfind("color:", 0) == 0) {
            ibl::EnvironmentSource src = ibl::parse_environment(e);
            obj = {{"type", "color"}, {"color", {src.color.x, src.color.y, src.color.z}}};
        } else {
            obj = {{"file", e}};
        }
        doc["environment"] = obj;
    }
    for (const auto& [ptr, value] : b.sweep) {
        try {
            doc[json::json_pointer(ptr)] = value;
        } catch (const json::exception& e) {
            throw Error(name, ptr, std::string("the sweep cannot set it: ") + e.what());
        }
    }
    return parse_scene_document(doc, name, base, defaults, diag, so).job;
}

struct Worker {
    std::unique_ptr<gpu::Context> context;
    std::unique_ptr<Renderer> renderer;
    std::shared_ptr<const Scene> scene;  // what the renderer holds
    int scene_index = -2;
    std::shared_ptr<const VertexOcclusion> occlusion;  // what the renderer holds (--ao baked)
};

// Baked occlusion (--ao baked) shared by the jobs that draw one loaded scene with the same
// rays: baked once, while the scene is held (an entry whose scene is gone is dropped).
class OcclusionCache {
public:
    std::shared_ptr<const VertexOcclusion> get(const Job& job, const std::shared_ptr<const Scene>& scene, int scene_index) {
        if (job.output.ao != AmbientOcclusion::Baked) return nullptr;
        std::lock_guard lock(mutex_);
        std::erase_if(entries_, [](const Entry& e) { return e.scene.expired(); });
        for (const Entry& e : entries_)
            if (e.scene.lock() == scene && e.scene_index == scene_index && e.rays == job.output.ao_rays) return e.value;
        auto value = std::make_shared<const VertexOcclusion>(*trace::job_vertex_occlusion(job, *scene, scene_index));
        entries_.push_back({scene, scene_index, job.output.ao_rays, value});
        return value;
    }

private:
    struct Entry {
        std::weak_ptr<const Scene> scene;
        int scene_index = -1, rays = 0;
        std::shared_ptr<const VertexOcclusion> value;
    };
    std::mutex mutex_;
    std::vector<Entry> entries_;
};

int run_batch(const BatchOptions& o, const CLI::App* cmd) {
    auto t_start = Clock::now();
    std::optional<Job> defaults = job_from_options(o.render, Job{});
    if (!defaults) return kExitUsage;
    long shard = 0, shards = 1;
    if (!parse_shard(o, shard, shards)) return kExitUsage;
    if (o.format != "png" && o.format != "exr" && o.format != "hdr") {
        print_error("--format: png, exr or hdr");
        return kExitUsage;
    }
    const fs::path out_dir(o.out);
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec) throw Error(o.out, "", "cannot create the output folder: " + ec.message());
    std::vector<BatchJob> all = read_job_list(o, folder_ignores_case(out_dir));
    std::vector<const BatchJob*> mine;
    for (const auto& j : all)
        if (long(j.index % std::size_t(shards)) == shard) mine.push_back(&j);
    // Temporaries a killed run of this machine left (fresnel/core/atomic_file.h); the log of
    // committed outputs, which --resume trusts (batch_outputs.h).
    remove_stale_temporaries_in(out_dir);
    const std::map<std::string, OutputLog::Entry> committed =
        o.resume ? OutputLog::read(out_dir) : std::map<std::string, OutputLog::Entry>{};
    OutputLog output_log(OutputLog::file_for(out_dir, shard, shards));

    Caches caches(std::max<std::size_t>(o.cache_models, std::size_t(o.workers)));
    BatchProgress progress(mine.size());
    std::mutex print_mutex;
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> failed{0}, rendered{0}, skipped{0};

    auto report = [&](const json& j, bool ok, const std::string& text) {
        std::lock_guard lock(print_mutex);
        if (o.render.json) std::printf("%s\n", j.dump().c_str());
        else if (!ok) std::printf("FAILED %s\n", text.c_str());
        else std::printf("%s\n", text.c_str());
        std::fflush(stdout);
    };

    // Each worker is a pipeline of three stages, so the GL thread mostly draws: the next job is
    // read and its model loaded (and its environment) in the background while this one is
    // drawn, and the image is encoded and written in the background while the next is drawn.
    struct Task {
        const BatchJob* b = nullptr;
        fs::path output;
        json r;
        Clock::time_point t_job;
        Diagnostics diag;
        bool skip = false;
        std::string error;  // set: failed
        Job job;
        std::shared_ptr<const Scene> scene;
        ResolvedJob resolved;
        std::shared_ptr<const ibl::BakedIbl> env;
        std::shared_ptr<const ImageF> lut;
        std::shared_ptr<const VertexOcclusion> occlusion;  // --ao baked
        ImageF image;
    };
    OcclusionCache occlusion_cache;
    auto failure = [](const BatchJob& b, const std::exception& e) {
        std::string what = e.what();
        return what.rfind(b.label, 0) == 0 ? what : b.label + ": " + what;
    };
    // Stage 1 (background): the job read, its model and environment loaded.
    auto prepare = [&](const BatchJob* b, int w) {
        auto t = std::make_shared<Task>();
        t->b = b;
        t->output = out_dir / b->output;
        t->t_job = Clock::now();
        t->r = {{"index", b->index}, {"job", b->label}, {"output", t->output.string()}, {"worker", w}};
        try {
            if (!b->error.empty()) throw std::runtime_error(b->error);
            std::error_code e;
            if (o.resume && fs::is_regular_file(t->output, e)) {
                if (OutputLog::verified(committed, b->output, t->output)) {
                    t->skip = true;
                    return t;
                }
                t->diag.warn(t->output.string(), "",
                             "is not the output the batch log recorded (written by another run, changed or cut "
                             "short): rendered again");
            }
            t->job = read_job(*b, *defaults, o.render.allow_external(), t->diag);
            std::string ext = lower_extension(t->output.string());
            t->job.output.float_output = ext == ".exr" || ext == ".hdr";
            auto t_load = Clock::now();
            bool loaded = false;
            t->scene = caches.scene(t->job, t->diag, loaded);
            t->r["load_ms"] = ms_since(t_load);
            t->r["model_cached"] = !loaded;
            t->resolved = resolve(t->job, *t->scene, &t->diag);
            auto t_env = Clock::now();
            if (t->resolved.environment) t->env = caches.environment(t->resolved);
            if (t->resolved.needs_brdf_lut) t->lut = caches.brdf_lut(t->resolved);
            t->r["environment_ms"] = ms_since(t_env);
            if (t->job.output.ao == AmbientOcclusion::Baked) {
                auto t_ao = Clock::now();
                t->occlusion = occlusion_cache.get(t->job, t->scene, t->resolved.scene_index);
                t->r["ao_ms"] = ms_since(t_ao);
            }
        } catch (const Error& e) {
            t->error = e.what();
        } catch (const std::bad_alloc&) {
            t->error = b->label + ": out of memory";
        } catch (const std::exception& e) {
            t->error = failure(*b, e);
        }
        return t;
    };
    // Stage 3 (background): the image written atomically, the result reported.
    auto finish = [&](std::shared_ptr<Task> t) {
        std::string text;
        if (t->error.empty() && !t->skip) {
            try {
                std::error_code e;
                fs::create_directories(t->output.parent_path().empty() ? fs::path(".") : t->output.parent_path(), e);
                write_image(t->output.string(), t->image, t->resolved.transparent());
                output_log.record(t->b->output, t->output);  // done only once recorded: --resume trusts it
            } catch (const Error& e) {
                t->error = e.what();
            } catch (const std::exception& e) {
                t->error = failure(*t->b, e);
            }
        }
        t->image = ImageF();
        if (!t->error.empty()) {
            t->r["status"] = "failed";
            t->r["error"] = t->error;
            text = t->error.rfind(t->b->label, 0) == 0 ? t->error : t->b->label + ": " + t->error;
            ++failed;
        } else if (t->skip) {
            t->r["status"] = "skipped";
            text = "skipped " + t->output.string() + " (exists)";
            ++skipped;
        } else {
            t->r["status"] = "ok";
            char ms[32];
            std::snprintf(ms, sizeof ms, "%.0f ms", ms_since(t->t_job));
            text = "ok " + t->output.string() + " (" + ms + ")";
            ++rendered;
        }
        t->r["total_ms"] = ms_since(t->t_job);
        t->r["rss_mib"] = resident_mib();  // a leak per job shows as a climb (bench/batch_bench.py)
        t->r["warnings"] = t->diag.lines();
        report(t->r, t->error.empty(), text);
        progress.job_done(!t->error.empty(), t->skip);
    };
    auto work = [&](int w) {
        Worker worker;
        std::size_t i = next++;
        std::future<std::shared_ptr<Task>> pending;
        if (i < mine.size()) pending = std::async(std::launch::async, prepare, mine[i], w);
        std::future<void> writing;
        while (i < mine.size()) {
            std::shared_ptr<Task> t = pending.get();
            std::size_t j = next++;
            if (j < mine.size()) pending = std::async(std::launch::async, prepare, mine[j], w);
            // Stage 2 (this thread, which owns the GL context): upload when the scene changed, draw.
            if (t->error.empty() && !t->skip) {
                try {
                    if (!worker.context) {
                        worker.context = gpu::create_headless_context(context_options(o.render));
                        worker.renderer = std::make_unique<Renderer>(*worker.context);
                    }
                    auto t_upload = Clock::now();
                    if (worker.scene != t->scene || worker.scene_index != t->resolved.scene_index) {
                        worker.renderer->set_scene(*t->scene, t->resolved.scene_index);
                        worker.scene = t->scene;
                        worker.scene_index = t->resolved.scene_index;
                        worker.occlusion = nullptr;  // set_scene dropped it
#ifdef __GLIBC__
                        // The previous model's images and meshes are freed by now (unless cached):
                        // give the pages back, so resident memory follows what is held.
                        ::malloc_trim(0);
#endif
                    }
                    if (worker.occlusion != t->occlusion) {
                        worker.renderer->set_vertex_occlusion(t->occlusion.get());
                        worker.occlusion = t->occlusion;
                    }
                    t->r["upload_ms"] = ms_since(t_upload);
                    RenderSettings rs = t->resolved.settings;
                    rs.environment = t->env.get();
                    rs.brdf_lut = t->lut.get();
                    auto t_frame = Clock::now();
                    FrameStats stats;
                    t->image = worker.renderer->render(t->resolved.camera, t->resolved.lights, rs, &stats);
                    t->r["frame_ms"] = ms_since(t_frame);
                    if (!stats.gl_errors.empty()) throw Error("OpenGL", "", "the frame raised " + stats.gl_errors);
                } catch (const Error& e) {
                    t->error = e.what();
                } catch (const std::bad_alloc&) {
                    t->error = t->b->label + ": out of memory";
                } catch (const std::exception& e) {
                    t->error = failure(*t->b, e);
                }
            }
            if (writing.valid()) writing.get();
            writing = std::async(std::launch::async, finish, t);
            i = j;
        }
        if (writing.valid()) writing.get();
    };
    const int workers = std::max(1, std::min<int>(o.workers, int(std::max<std::size_t>(mine.size(), 1))));
    if (workers == 1) {
        work(0);
    } else {
        std::vector<std::thread> threads;
        for (int w = 0; w < workers; ++w) threads.emplace_back(work, w);
        for (auto& t : threads) t.join();
    }
    double s = ms_since(t_start) / 1000.0;
    std::fprintf(stderr, "fresnel: batch: %zu rendered, %zu skipped, %zu failed of %zu (shard %ld/%ld of %zu jobs) in %.1f s",
                 rendered.load(), skipped.load(), failed.load(), mine.size(), shard, shards, all.size(), s);
    if (rendered > 0 && s > 0) std::fprintf(stderr, ", %.0f images/hour", double(rendered) / s * 3600.0);
    std::fprintf(stderr, "\n");
    (void)cmd;
    return failed > 0 ? kExitBadInput : kExitOk;
}

}  // namespace

Runner add_batch_command(CLI::App& app) {
    auto o = std::make_shared<BatchOptions>();
    CLI::App* cmd = app.add_subcommand(
        "batch", "Render many jobs in one process: a JSON Lines job list or a folder of models (docs/batch.md)");
    cmd->footer("Examples:\n"
                "  fresnel batch models/ --out thumbs --size 256             # a thumbnail of every model\n"
                "  fresnel batch jobs.jsonl --out renders --jobs 2 --json    # one JSON line per job\n"
                "  fresnel batch jobs.jsonl --out out --shard auto --resume  # a shard of a Slurm/Kubernetes array\n");
    cmd->add_option("jobs", o->jobs,
                    "A .jsonl file (one job a line: a scene file, a model, or a model with scene-file keys inline, "
                    "plus \"output\" and \"sweep\") or a folder of models (.gltf, .glb, .obj and .fresnel.json "
                    "scene files: a thumbnail each)")
        ->required();
    cmd->add_option("--out", o->out, "Output folder; job outputs are named after their scene file or model")
        ->capture_default_str();
    cmd->add_option("--shard", o->shard,
                    "I/N: only the jobs whose index is I modulo N; auto: I and N from SLURM_ARRAY_TASK_ID "
                    "(minus SLURM_ARRAY_TASK_MIN) and SLURM_ARRAY_TASK_COUNT, or JOB_COMPLETION_INDEX and "
                    "--shard-count / FRESNEL_SHARD_COUNT (Kubernetes Indexed Jobs)");
    cmd->add_option("--shard-count", o->shard_count, "N for --shard auto (else from the environment)")
        ->check(CLI::Range(1, 1 << 30));
    cmd->add_option("--jobs,-j", o->workers, "Workers, each with its own GL context")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    cmd->add_flag("--resume", o->resume,
                  "Skip jobs whose output exists as the batch log in --out recorded it (size and checksum; "
                  "other files are rendered again)");
    cmd->add_option("--format", o->format, "Output format of jobs that name no output: png, exr or hdr")
        ->capture_default_str();
    cmd->add_option("--cache-models", o->cache_models, "Loaded models kept between jobs")->capture_default_str();
    cmd->add_flag("--json", o->render.json,
                  "One JSON line per job on stdout: index, job, output, status (ok, skipped, failed), error, "
                  "timings, warnings");
    add_job_flags(cmd, o->render);
    return [o, cmd] { return run_batch(*o, cmd); };
}

}  // namespace fresnel::cli
