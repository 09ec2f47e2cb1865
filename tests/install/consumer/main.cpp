// Uses only the installed package: prints fresnel::version(), renders one sphere headless
// into an image in memory and checks that the sphere is in the centre and the background
// in the corners. Exits non-zero (with the reason) otherwise.
#include <fresnel/fresnel.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

namespace {

float max_rgb(const fresnel::ImageF& image, int x, int y) {
    const float* p = image.at(x, y);
    return std::max({p[0], p[1], p[2]});
}

int fail(const std::string& why) {
    std::fprintf(stderr, "consumer: %s\n", why.c_str());
    return 1;
}

}  // namespace

int main() {
    std::printf("fresnel %.*s\n", int(fresnel::version().size()), fresnel::version().data());
    try {
        fresnel::Scene scene;
        scene.source = "(one sphere)";
        fresnel::Material material;
        material.base_color_factor = {0.8f, 0.3f, 0.2f, 1.0f};
        material.metallic_factor = 0.0f;
        material.roughness_factor = 0.5f;
        scene.materials.push_back(material);
        fresnel::Mesh mesh;
        fresnel::Primitive sphere = fresnel::make_uv_sphere();
        sphere.material = 0;
        mesh.primitives.push_back(std::move(sphere));
        scene.meshes.push_back(std::move(mesh));
        fresnel::Node node;
        node.mesh = 0;
        scene.nodes.push_back(node);
        scene.scenes.push_back({0});

        const int size = 64;
        auto instances = fresnel::flatten(scene);
        fresnel::CameraSetup camera = fresnel::orbit_camera(fresnel::scene_bounds(scene, instances), {}, size, size);
        auto context = fresnel::gpu::create_headless_context();
        fresnel::Renderer renderer(*context);
        renderer.set_scene(scene);
        fresnel::RenderSettings settings;
        settings.width = settings.height = size;
        settings.background = {0.0f, 0.0f, 0.0f, 1.0f};
        fresnel::FrameStats stats;
        fresnel::ImageF image = renderer.render(camera, fresnel::default_lights(), settings, &stats);
        if (!stats.gl_errors.empty()) return fail("OpenGL errors: " + stats.gl_errors);
        if (image.width != size || image.height != size) return fail("the image has the wrong size");

        // The sphere covers the centre (lit from the front by the default key light) ...
        float centre_min = 1.0f;
        for (int y = size / 2 - 4; y < size / 2 + 4; ++y)
            for (int x = size / 2 - 4; x < size / 2 + 4; ++x) centre_min = std::min(centre_min, max_rgb(image, x, y));
        // ... and the background (black) the corners.
        float corner_max = std::max({max_rgb(image, 0, 0), max_rgb(image, size - 1, 0), max_rgb(image, 0, size - 1),
                                     max_rgb(image, size - 1, size - 1)});
        std::printf("rendered %dx%d on %s: centre min %.3f, corners max %.3f, %zu triangles\n", size, size,
                    context->renderer().c_str(), centre_min, corner_max, stats.triangles);
        if (centre_min < 0.05f) return fail("no sphere in the centre of the image");
        if (corner_max > 0.01f) return fail("the corners are not the background");
    } catch (const std::exception& e) {
        return fail(e.what());
    }
    std::printf("consumer: ok\n");
    return 0;
}
