#pragma once
// Scenes and cameras the viewer tests share: a unit box in front of a sphere, seen from +Z.
#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/job/camera.h"
#include "fresnel/scene/animation.h"
#include "fresnel/scene/procedural.h"
#include "fresnel/scene/scene.h"

namespace fresnel::viewer::test {

// An axis-aligned box from -h to +h: 12 triangles, material `material`.
inline Primitive make_box(float h, int material) {
    Primitive p;
    for (int i = 0; i < 8; ++i) p.positions.push_back(glm::vec3((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h));
    p.normals.assign(8, glm::vec3(0.0f, 0.0f, 1.0f));
    // Two triangles per face: the four corners with bit `axis` equal to `side`.
    for (int axis : {1, 2, 4})
        for (int side : {0, 1}) {
            std::uint32_t q[4];
            int n = 0;
            for (std::uint32_t i = 0; i < 8; ++i)
                if (((i & std::uint32_t(axis)) != 0) == (side == 1)) q[n++] = i;
            // q[0], q[1], q[3], q[2] go round the face (the two other bits count up in binary).
            p.indices.insert(p.indices.end(), {q[0], q[1], q[3], q[0], q[3], q[2]});
        }
    p.bounds_min = glm::vec3(-h);
    p.bounds_max = glm::vec3(h);
    p.material = material;
    return p;
}

// Node 0: a box (half size 0.5) at the origin, material 0; node 1: a unit sphere at z = -3,
// material 1. Both roots of scene 0.
inline Scene box_before_sphere() {
    Scene s;
    Mesh box, sphere;
    box.primitives.push_back(make_box(0.5f, 0));
    Primitive ball = make_uv_sphere(64, 32);
    ball.material = 1;
    sphere.primitives.push_back(ball);
    s.meshes = {box, sphere};
    s.materials.resize(2);
    s.materials[0].name = "box";
    s.materials[1].name = "ball";
    Node a, b;
    a.name = "box";
    a.mesh = 0;
    b.name = "ball";
    b.mesh = 1;
    b.translation = glm::vec3(0.0f, 0.0f, -3.0f);
    b.local = glm::translate(glm::mat4(1.0f), b.translation);
    s.nodes = {a, b};
    s.scenes = {{0, 1}};
    return s;
}

// box_before_sphere with two animations: 0 "slide" moves the box along +X from 0 at 0 s to 4 at
// 2 s; 1 "lift" moves the sphere along +Y from 0 at 1 s to 3 at 4 s (linear).
inline Scene animated_box_before_sphere() {
    Scene s = box_before_sphere();
    auto track = [](std::string name, int node, float t0, float t1, glm::vec3 from, glm::vec3 to) {
        Animation a;
        a.name = std::move(name);
        AnimationSampler sampler;
        sampler.input = {t0, t1};
        sampler.output = {from.x, from.y, from.z, to.x, to.y, to.z};
        sampler.width = 3;
        a.samplers.push_back(sampler);
        AnimationChannel c;
        c.sampler = 0;
        c.node = node;
        c.path = AnimationPath::Translation;
        a.channels.push_back(c);
        return a;
    };
    s.animations.push_back(track("slide", 0, 0.0f, 2.0f, glm::vec3(0.0f), glm::vec3(4.0f, 0.0f, 0.0f)));
    s.animations.push_back(track("lift", 1, 1.0f, 4.0f, glm::vec3(0.0f, 0.0f, -3.0f), glm::vec3(0.0f, 3.0f, -3.0f)));
    return s;
}

// A 60-degree camera at (0, 0, 5) looking at the origin, for a 200 x 100 window.
inline CameraSetup camera_from_z(const Bounds& bounds) {
    return look_at_camera(bounds, glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 60.0f, 200, 100);
}

}  // namespace fresnel::viewer::test
