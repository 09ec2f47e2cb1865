// The material property registry (fresnel/material/properties.h): each property reads its
// default from a default material, writes where it reads, adds its block with defaults that
// change nothing else, and parses and prints its own text; bad text gets one message format.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "fresnel/core/error.h"
#include "fresnel/material/properties.h"

namespace mp = fresnel::material_properties;
using fresnel::Material;

namespace {

// A value of the property other than its default, inside its range.
mp::Value other_value(const mp::Property& p) {
    mp::Value v{};
    for (int k = 0; k < p.width; ++k)
        v[std::size_t(k)] = p.type == mp::Type::Bool     ? 1.0f - p.fallback[0]
                            : p.type == mp::Type::Choice ? 2.0f
                                                         : p.slider_min + (0.3f + 0.1f * float(k)) * (p.slider_max - p.slider_min);
    return v;
}

}  // namespace

TEST(MaterialProperties, NamesPathsAndBlocksAreUniqueAndKnown) {
    std::set<std::string_view> names, paths;
    for (const mp::Property& p : mp::all()) {
        EXPECT_TRUE(names.insert(p.name).second) << p.name;
        EXPECT_TRUE(paths.insert(p.path).second) << p.path;
        EXPECT_EQ(mp::find(p.name), &p);
        EXPECT_EQ(mp::find_path(p.path), &p);
        EXPECT_FALSE(p.doc.empty()) << p.name;
        if (!p.block.empty()) {
            EXPECT_NE(mp::find_block(p.block), nullptr) << p.name;
            EXPECT_EQ(p.path.substr(0, 11 + p.block.size()), "extensions/" + std::string(p.block)) << p.name;
        }
        EXPECT_LE(p.min, p.slider_min) << p.name;
        EXPECT_GE(p.max, p.slider_max) << p.name;
        EXPECT_LT(p.slider_min, p.slider_max) << p.name;
        EXPECT_EQ(mp::check(p, p.fallback), "") << p.name;  // the default is a value
        if (p.animatable) {
            EXPECT_NE(p.data, nullptr) << p.name;
        }
    }
    for (const mp::Texture& t : mp::textures()) {
        EXPECT_EQ(mp::find_texture_path(t.path), &t);
        if (!t.block.empty()) {
            EXPECT_NE(mp::find_block(t.block), nullptr) << t.name;
        }
    }
    EXPECT_EQ(mp::find("nonsense"), nullptr);
    EXPECT_NE(mp::find("diffuseRoughnessFactor"), nullptr);
}

TEST(MaterialProperties, DefaultsAreTheMaterialsAndAddingABlockChangesNothing) {
    const Material plain;
    for (const mp::Property& p : mp::all()) {
        EXPECT_TRUE(mp::same(p, p.get(plain), p.fallback)) << p.name << " reads " << mp::format(p, p.get(plain));
        EXPECT_EQ(mp::present(p, plain), p.block.empty()) << p.name;
    }
    for (const mp::Block& b : mp::blocks()) {
        Material m;
        EXPECT_FALSE(b.present(m)) << b.name;
        b.add(m);
        EXPECT_TRUE(b.present(m)) << b.name;
        // Every property still reads its default: a block added with its defaults changes nothing.
        for (const mp::Property& p : mp::all()) EXPECT_TRUE(mp::same(p, p.get(m), p.fallback)) << b.name << " " << p.name;
        b.remove(m);
        EXPECT_FALSE(b.present(m)) << b.name;
    }
}

TEST(MaterialProperties, PutGetAndDataAgreeAndTouchOneProperty) {
    for (const mp::Property& p : mp::all()) {
        Material m;
        const mp::Value v = other_value(p);
        ASSERT_EQ(mp::check(p, v), "") << p.name;
        p.put(m, v);
        EXPECT_TRUE(mp::present(p, m)) << p.name;  // the block was added
        EXPECT_TRUE(mp::same(p, p.get(m), v)) << p.name;
        for (const mp::Property& q : mp::all()) {
            if (&q != &p) {
                EXPECT_TRUE(mp::same(q, q.get(m), q.fallback)) << p.name << " changed " << q.name;
            }
        }
        if (p.data) {
            Material n;
            float* f = p.data(n);
            for (int k = 0; k < p.width; ++k) f[k] = v[std::size_t(k)];
            EXPECT_TRUE(mp::same(p, p.get(n), v)) << p.name;
        }
    }
}

TEST(MaterialProperties, TextRoundTripsAndBadTextHasOneMessage) {
    for (const mp::Property& p : mp::all()) {
        const mp::Value v = other_value(p);
        const std::string text = mp::format(p, v);
        EXPECT_TRUE(mp::same(p, mp::parse(p, text, "here"), v)) << p.name << " " << text;
        EXPECT_TRUE(mp::same(p, mp::parse(p, mp::format(p, p.fallback), "here"), p.fallback)) << p.name;
    }
    const mp::Property& base = *mp::find("baseColorFactor");
    EXPECT_TRUE(mp::same(base, mp::parse(base, "1 0.5 0 1", "x"), mp::Value{1, 0.5f, 0, 1}));
    const mp::Property& rough = *mp::find("roughnessFactor");
    auto message = [](const mp::Property& p, const std::string& text) {
        try {
            mp::parse(p, text, "scene.json /models/0/materials/0/" + std::string(p.name));
        } catch (const fresnel::Error& e) {
            return e.file() + ": " + e.reason();
        }
        return std::string("accepted");
    };
    EXPECT_EQ(message(rough, "2"), "scene.json /models/0/materials/0/roughnessFactor: expected a number in [0, 1], got '2'");
    EXPECT_EQ(message(rough, "x"), "scene.json /models/0/materials/0/roughnessFactor: expected a number in [0, 1], got 'x'");
    EXPECT_EQ(message(base, "1,0,0"), "scene.json /models/0/materials/0/baseColorFactor: expected R,G,B,A in [0, 1], got '1,0,0'");
    EXPECT_EQ(message(*mp::find("alphaMode"), "HALF"),
              "scene.json /models/0/materials/0/alphaMode: expected OPAQUE, MASK or BLEND, got 'HALF'");
    EXPECT_EQ(message(*mp::find("ior"), "nan"), "scene.json /models/0/materials/0/ior: expected a number >= 0, got 'nan'");
    // Infinity only where it is the default (attenuationDistance: no absorption).
    EXPECT_EQ(message(*mp::find("attenuationDistance"), "inf"), "accepted");
    EXPECT_NE(message(*mp::find("ior"), "inf"), "accepted");

    Material m;
    mp::set(m, "clearcoatFactor", "0.5", "script.txt line 3");
    ASSERT_TRUE(m.clearcoat);
    EXPECT_FLOAT_EQ(m.clearcoat->clearcoat_factor, 0.5f);
    EXPECT_THROW(mp::set(m, "clearcoat", "0.5", "script.txt line 3"), fresnel::Error);
}

TEST(MaterialProperties, EditableHidesScalarsOfMissingTextures) {
    Material m;
    EXPECT_FALSE(mp::editable(*mp::find("normalScale"), m));
    EXPECT_TRUE(mp::editable(*mp::find("roughnessFactor"), m));
    EXPECT_FALSE(mp::editable(*mp::find("clearcoatFactor"), m));
    m.normal.texture = 0;
    EXPECT_TRUE(mp::editable(*mp::find("normalScale"), m));
    m.clearcoat.emplace();
    EXPECT_TRUE(mp::editable(*mp::find("clearcoatFactor"), m));
    EXPECT_FALSE(mp::editable(*mp::find("clearcoatNormalScale"), m));
}

TEST(MaterialProperties, DescribedAsJson) {
    const std::string j = mp::describe_json();
    for (const mp::Property& p : mp::all()) EXPECT_NE(j.find("\"name\":\"" + std::string(p.name) + "\""), std::string::npos);
    for (const mp::Block& b : mp::blocks()) EXPECT_NE(j.find("\"name\":\"" + std::string(b.name) + "\""), std::string::npos);
    EXPECT_NE(j.find("\"max\":null"), std::string::npos);  // infinite bounds
}
