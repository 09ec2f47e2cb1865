#pragma once
// The material property registry: every property of the core material and of each extension
// block declared once, with its glTF JSON path, type, range, default, whether
// KHR_animation_pointer may animate it, and how its block is created. What reads or writes a
// material property by name goes through it: the animation-pointer resolver, the view
// script's `set material`, the web page's editor, the viewer's widgets and its edits-to-
// overrides diff, scene-file material overrides (reader, writer, job_models) and the glTF
// writer's patcher. A property added here is offered by all of them.
//
// Names are the glTF property's own (metallicFactor, clearcoatFactor), except the scalars of
// a texture reference, named after their texture: normalScale (normalTexture/scale),
// occlusionStrength, clearcoatNormalScale.
//
// Blocks: a property of an extension the material does not have is set by adding the block
// with the specification's defaults first. Every ratified extension chooses defaults that
// change nothing (a factor of 0, an ior of 1.5), so adding a block is never visible until a
// value changes; the front ends all create blocks, none refuses.
//
// Values are exchanged as up to four floats (Value): numbers and colours as themselves, a
// boolean as 0/1, a choice as its index. As text: "0.5", "1,0,0" (or "1 0 0"), "MASK",
// "true"; bad text gets one message format: "<where>: expected <what>, got '<text>'".
#include <array>
#include <span>
#include <string>
#include <string_view>

#include "fresnel/material/material.h"

namespace fresnel::material_properties {

enum class Type {
    Number,  // `width` floats in [min, max] (a vector when width > 1)
    Color,   // RGB or RGBA (width 3 or 4) in [min, max]: editors show a colour picker
    Bool,    // false/true (0/1)
    Choice,  // one of `choices` (its index)
};

using Value = std::array<float, 4>;  // the first `width` are used

struct Property {
    std::string_view name;   // "clearcoatFactor": scene files, view scripts, the web page, the viewer
    std::string_view path;   // under the material: "extensions/KHR_materials_clearcoat/clearcoatFactor"
    std::string_view block;  // the extension ("KHR_materials_clearcoat"); empty: the core material
    Type type = Type::Number;
    int width = 1;
    float min = 0.0f, max = 1.0f;                // the specification's range (inclusive; ±inf: none)
    float slider_min = 0.0f, slider_max = 1.0f;  // the editors' range (within min..max)
    Value fallback{};                            // the specification's default
    bool animatable = false;                     // KHR_animation_pointer may name it
    std::span<const std::string_view> choices;   // Choice
    std::string_view unit;                       // "nm", "radians", "" (the value's own unit)
    std::string_view doc;                        // one line
    // The value in a material (the default when its block is absent).
    Value (*get)(const Material&) = nullptr;
    // Writes a value (the block is added with its defaults first). No range check: use check().
    void (*put)(Material&, const Value&) = nullptr;
    // The floats themselves (the block added first), for animation: Number and Color only.
    float* (*data)(Material&) = nullptr;
};

// An extension block a property can belong to.
struct Block {
    std::string_view name;  // "KHR_materials_clearcoat"
    std::string_view doc;
    bool (*present)(const Material&) = nullptr;
    void (*add)(Material&) = nullptr;  // with the specification's defaults (changes nothing)
    void (*remove)(Material&) = nullptr;
};

// A texture reference of the material, by its glTF path (KHR_texture_transform of it may be animated).
struct Texture {
    std::string_view name;   // "clearcoatTexture"
    std::string_view path;   // "extensions/KHR_materials_clearcoat/clearcoatTexture"
    std::string_view block;  // empty: core
    std::string_view channels;  // what it holds: "RGB sRGB", "R", "G roughness, B metallic"
    const TextureSlot* (*get)(const Material&) = nullptr;  // nullptr when the block is absent
    TextureSlot* (*slot)(Material&) = nullptr;             // the block added first
};

std::span<const Property> all();
std::span<const Block> blocks();
std::span<const Texture> textures();

const Property* find(std::string_view name);       // by name; nullptr when unknown
const Property* find_path(std::string_view path);  // by glTF path under the material
const Block* find_block(std::string_view name);
const Texture* find_texture_path(std::string_view path);

// Whether the property's block is in the material (always for core properties).
bool present(const Property& p, const Material& m);

// Whether an edit from `was` to `now` set the property: it is in `now` and was absent from
// `was` or differs (what savers write and the viewer keeps as overrides).
bool changed(const Property& p, const Material& was, const Material& now);

// Whether an editor shows it: its block is present and, for a texture's scalar
// (normalScale), the texture is there.
bool editable(const Property& p, const Material& m);

// What the property takes, for messages and docs: "a number in [0, 1]", "R,G,B in [0, 1]",
// "OPAQUE, MASK or BLEND", "true or false".
std::string expected(const Property& p);
// Why `v` is not a value of `p` ("" when it is one): the same words as expected().
std::string check(const Property& p, const Value& v);
// Parses text ("0.5", "1,0,0", "1 0 0", "MASK", "true") into a checked value; throws
// fresnel::Error(where, "", "expected <what>, got '<text>'") otherwise.
Value parse(const Property& p, std::string_view text, const std::string& where);
// A checked value from floats (a script's numbers, JSON arrays); throws as parse() does.
Value from_floats(const Property& p, std::span<const float> values, const std::string& where);
// The value as parse() reads it: shortest numbers joined by ',', a choice's word, true/false.
std::string format(const Property& p, const Value& v);
// Equal in the property's `width` components.
bool same(const Property& p, const Value& a, const Value& b);

// Sets a property of a material from text: find + parse + put, with errors naming `where`
// and the key (`fresnel settings` lists the properties).
void set(Material& m, std::string_view name, std::string_view text, const std::string& where);

// The registry as JSON (`fresnel settings --materials --json`, the web page's editor, the scene
// schema): [{name, path, block, type, width, min, max, sliderMin, sliderMax, default,
// animatable, unit, choices, expected, doc}], infinite bounds as null; then the blocks.
std::string describe_json();

}  // namespace fresnel::material_properties
