#pragma once
// glTF 2.0 animations: keyframe samplers and the channels that drive a node's translation,
// rotation, scale or morph weights, or (KHR_animation_pointer) a material, light or camera
// property named by a JSON pointer, and their evaluation at a time t (glTF 2.0 section 3.11
// and Appendix C):
//  - times before the first keyframe take the first value, after the last the last one;
//  - STEP holds the value of the keyframe at or before t;
//  - LINEAR interpolates linearly, except rotations: spherical linear interpolation along
//    the shorter arc (the second quaternion is negated when the dot product is negative);
//  - CUBICSPLINE is the cubic Hermite spline of Appendix C with the file's in- and
//    out-tangents scaled by the keyframe interval; rotations are normalised afterwards.
// The types are plain data (the glTF loader fills and validates them; fresnel/scene/pose.h
// applies them to a Scene).
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace fresnel {

enum class Interpolation { Linear, Step, CubicSpline };
// Pointer: KHR_animation_pointer on anything but a node's TRS and weights (which the loader
// turns into the other paths); AnimationChannel::pointer names the property.
enum class AnimationPath { Translation, Rotation, Scale, Weights, Pointer };

struct AnimationSampler {
    std::vector<float> input;  // keyframe times in seconds, strictly increasing, finite
    // `width` floats per keyframe (x, y, z / quaternion x, y, z, w / one weight per morph
    // target); CUBICSPLINE keyframes hold three values each: in-tangent, value, out-tangent.
    std::vector<float> output;
    int width = 0;
    Interpolation interpolation = Interpolation::Linear;
    // True when output holds exactly input.size() (x3 for CUBICSPLINE) values of `width` floats.
    bool consistent() const;
};

struct AnimationChannel {
    int sampler = -1;  // index into Animation::samplers
    int node = -1;     // target node (-1 for Pointer channels)
    AnimationPath path = AnimationPath::Translation;
    // Path Pointer: the JSON pointer, e.g. "/materials/0/pbrMetallicRoughness/baseColorFactor"
    // (fresnel/scene/pose.h: animation_pointer_width lists what fresnel animates).
    std::string pointer;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;
    // The earliest first keyframe and the latest last keyframe over the samplers (0 when none).
    float start() const;
    float end() const;
    float duration() const { return end() - start(); }
};

// The sampler's value at time t: `width` floats written to `out` (out.size() >= width).
// Rotations (width 4) should use sample_rotation, which interpolates on the sphere. The
// sampler must be consistent(); an empty sampler writes nothing.
void sample(const AnimationSampler& s, float t, std::span<float> out);
std::vector<float> sample(const AnimationSampler& s, float t);

// A rotation sampler (width 4, glTF's x, y, z, w order) at time t: unit quaternion.
glm::quat sample_rotation(const AnimationSampler& s, float t);

// Spherical linear interpolation from a to b (unit quaternions) along the shorter arc;
// normalised linear interpolation when they are nearly parallel.
glm::quat slerp_shortest(const glm::quat& a, const glm::quat& b, float u);

}  // namespace fresnel
