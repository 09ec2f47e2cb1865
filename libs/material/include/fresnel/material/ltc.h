#pragma once
// Linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt 2016, "Real-Time Polygonal-Light
// Shading with Linearly Transformed Cosines") for fresnel's GGX lobe; shaders/ltc.glsl holds
// the same functions line by line.
//
// Method. The lobe f(l) = D(h) V(l, v) (n.l) of brdf.h (GGX, height-correlated Smith, alpha =
// perceptual roughness^2, no Fresnel), divided by its directional albedo, is approximated by a
// clamped cosine D_o(w_o) = max(w_o.z, 0) / pi seen through a 3x3 matrix M: the density of
// l = M w_o / |M w_o|. Integrating that density over a polygon is integrating the cosine over
// the polygon transformed by M^-1, which has a closed form (Lambert's edge sum). tools/ltc_fit
// fits M^-1 per (roughness, view angle) and writes it to a 64x64 table (src/ltc_table.inc),
// in the frame where n = +Z and v lies in the XZ plane with v.x >= 0:
//   M^-1 = [[a, 0, b], [0, c, 0], [d, 0, 1]] (rows), table texel (i, j) = (a, b, c, d),
//   i = roughness * 63 (x), j = t * 63 (y) with n.v = 1 - t^2, i.e. t = sqrt(1 - n.v) (Heitz's
//   parameterisation: about even steps in the view angle, finer in n.v near grazing).
// The magnitude (albedo) is not stored: with the split-sum table's scale A and bias B,
//   specular = polygon_integral(inverse_matrix(n.v, r), ...) * (F0 * A + F90 * B) * radiance.
//
// Errors. The fit is a best fit, not an identity: tools/ltc_fit prints the L1 distance
// (integral of |lobe - LTC| over the hemisphere, both normalised; it bounds twice the error of
// any polygon's share of the lobe). Typically a few per cent of the albedo, more at grazing
// views of rough surfaces, where GGX's shadowed, stretched lobe is least cosine-like and part
// of the LTC's mass falls below the horizon (and is lost). The table is bilinearly interpolated
// (as a GPU's linear filter does), roughness is floored at 0.02 in the fit and n.v at 1e-3.
// The polygon is clipped to the upper hemisphere exactly; the edge sum is exact up to float
// rounding. Spheres and disks are polygons with as many vertices as asked (sphere_polygon:
// a sphere covers the same cone of directions as a disk facing the point).
//
// Winding. Polygons are one-sided: their vertices run counter-clockwise seen from the lit
// (emitting) side, i.e. the right-hand normal (p1 - p0) x (p2 - p0) points towards the lit
// side, as OpenGL's front faces. Seen from the back the integral is 0. Points are positions
// relative to the shading point (p - x), in any consistent unit (only directions matter).
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace fresnel::ltc {

inline constexpr int kTableSize = 64;
// Most vertices a polygon may have; clipping to the horizon can add one (kMaxPolygon + 1).
inline constexpr int kMaxPolygon = 16;

// The table: kTableSize^2 texels of 4 floats (a, b, c, d), texel (i, j) at ((j * 64 + i) * 4),
// i = roughness, j = t (a 64x64 RGBA texture: x = roughness, y = t = sqrt(1 - n.v)).
const float* table_data();

// M^-1 at (n.v, perceptual roughness), column-major (glm), in the frame of polygon_integral:
// the bilinear, clamp-to-edge lookup a GPU's linear filter does at
// uv = (r, sqrt(1 - n.v)) * (63/64) + 0.5/64. Inputs are clamped to [0, 1].
glm::mat3 inverse_matrix(float n_dot_v, float perceptual_roughness);

// The integral of the normalised LTC distribution minv describes over the polygon `points`
// (count <= kMaxPolygon vertices, convex, positions relative to the shading point, counter-
// clockwise seen from the lit side), clipped to the hemisphere above n. The frame: t1 =
// normalize(v - n (v.n)) (any tangent when v is parallel to n), t2 = n x t1. With minv =
// identity: the diffuse form factor (cosine-weighted solid angle / pi). 0 for a back-facing
// polygon, one below the horizon, count < 3 or count > kMaxPolygon.
float polygon_integral(const glm::mat3& minv, glm::vec3 n, glm::vec3 v, const glm::vec3* points, int count);

// A regular polygon of `count` vertices (3..kMaxPolygon, clamped) with the disk's area (its
// circumradius is radius * sqrt(pi / (count/2 sin(2 pi / count)))), centred at `center` in the
// plane of the unit, orthogonal axes u and v, counter-clockwise around u x v (so lit on the
// u x v side). Writes `count` points to out; returns the count.
int disk_polygon(glm::vec3 center, glm::vec3 axis_u, glm::vec3 axis_v, float radius, glm::vec3* out, int count);

// A sphere of uniform radiance as the disk that covers the same cone of directions seen from
// shading_point: centred at the sphere's centre, perpendicular to the direction to the point,
// of radius r d / sqrt(d^2 - r^2) (d: distance to the centre), facing the point; then
// disk_polygon. Returns 0 (no points) when the point is inside the sphere or on it: callers
// treat the point as fully surrounded by the light (the integral is then 1).
// As everywhere, centre and point in the same space; pass points relative to the shading point
// to polygon_integral (e.g. centre - x and shading_point = 0).
int sphere_polygon(glm::vec3 center, float radius, glm::vec3 shading_point, glm::vec3* out, int count);

}  // namespace fresnel::ltc
