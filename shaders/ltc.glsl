// Linearly transformed cosines (Heitz, Dupuy, Hill and Neubelt 2016) for the GGX lobe of
// brdf.glsl; the same functions, line by line, as libs/material/src/ltc.cpp (see
// fresnel/material/ltc.h for the method, the table and its errors).
//
// u_ltc_table: the 64x64 RGBA16F table of fresnel::ltc::table_data(), linear filtered, clamped
// to its edges: texel (i, j) = (a, b, c, d) of M^-1 = [[a, 0, b], [0, c, 0], [d, 0, 1]] (rows)
// at roughness i / 63 (x) and n.v = 1 - (j / 63)^2 (y = sqrt(1 - n.v)).
// Polygons: positions relative to the shading point, at most LTC_MAX_POLYGON vertices,
// convex, counter-clockwise seen from the lit side (the right-hand normal points to it);
// one-sided (0 from behind). Specular = ltc_polygon_integral(...) * (F0 * A + F90 * B) * radiance.
// Needs PI (common.glsl).
const int LTC_TABLE_SIZE = 64;
const int LTC_MAX_POLYGON = 16;
uniform sampler2D u_ltc_table;

mat3 ltc_inverse_matrix(float n_dot_v, float roughness) {
    float r = clamp(roughness, 0.0, 1.0);
    float t = sqrt(1.0 - clamp(n_dot_v, 0.0, 1.0));
    vec2 uv = vec2(r, t) * (float(LTC_TABLE_SIZE - 1) / float(LTC_TABLE_SIZE)) + 0.5 / float(LTC_TABLE_SIZE);
    vec4 e = texture(u_ltc_table, uv);
    // Rows [[a, 0, b], [0, c, 0], [d, 0, 1]]; mat3 takes columns.
    return mat3(vec3(e.x, 0.0, e.w), vec3(0.0, e.z, 0.0), vec3(e.y, 0.0, 1.0));
}

// The clamped cosine's integral over the edge a -> b, times 2 pi (robust for nearly parallel a, b).
float ltc_edge_integral(vec3 a, vec3 b) {
    vec3 c = cross(a, b);
    float s = length(c);
    float theta = atan(s, dot(a, b));
    return c.z * (theta / max(s, 1e-7));
}

float ltc_polygon_integral(mat3 minv, vec3 n, vec3 v, vec3 points[17], int count) {
    if (count < 3 || count > LTC_MAX_POLYGON) return 0.0;
    // The frame: n = +Z, v in the XZ plane with v.x >= 0.
    vec3 t1 = v - n * dot(v, n);
    float len = length(t1);
    if (len > 1e-6) {
        t1 = t1 / len;
    } else {  // v parallel to n: any tangent
        t1 = abs(n.z) < 0.999 ? cross(vec3(0.0, 0.0, 1.0), n) : vec3(1.0, 0.0, 0.0);
        t1 = normalize(t1 - n * dot(t1, n));
    }
    vec3 t2 = cross(n, t1);
    // Into the frame, through M^-1, onto the unit sphere.
    vec3 p[17];
    for (int i = 0; i < LTC_MAX_POLYGON; ++i) {
        if (i >= count) break;
        vec3 q = minv * vec3(dot(points[i], t1), dot(points[i], t2), dot(points[i], n));
        float l = length(q);
        p[i] = l > 0.0 ? q / l : q;
    }
    // Clip to z >= 0 (Sutherland-Hodgman against one plane): at most one vertex more.
    vec3 c[17];
    int m = 0;
    for (int i = 0; i < LTC_MAX_POLYGON; ++i) {
        if (i >= count) break;
        vec3 a = p[i];
        vec3 b = p[i + 1 < count ? i + 1 : 0];
        if (a.z >= 0.0 && m <= LTC_MAX_POLYGON) c[m++] = a;
        if ((a.z >= 0.0) != (b.z >= 0.0) && m <= LTC_MAX_POLYGON) {
            vec3 x = a + (b - a) * (a.z / (a.z - b.z));
            x.z = 0.0;
            float l = length(x);
            c[m++] = l > 0.0 ? x / l : x;
        }
    }
    if (m < 3) return 0.0;
    float sum = 0.0;
    for (int i = 0; i < LTC_MAX_POLYGON + 1; ++i) {
        if (i >= m) break;
        sum += ltc_edge_integral(c[i], c[i + 1 < m ? i + 1 : 0]);
    }
    // Counter-clockwise seen from the lit side (below the polygon) is clockwise seen from +Z,
    // where the edge sum is negative.
    return max(-sum / (2.0 * PI), 0.0);
}

// A regular polygon of `count` vertices (3..16) with the disk's area, counter-clockwise around
// u x v (lit on the u x v side); returns the count.
int ltc_disk_polygon(vec3 center, vec3 axis_u, vec3 axis_v, float radius, out vec3 points[17], int count) {
    count = clamp(count, 3, LTC_MAX_POLYGON);
    float step = 2.0 * PI / float(count);
    float circumradius = radius * sqrt(PI / (0.5 * float(count) * sin(step)));
    for (int k = 0; k < LTC_MAX_POLYGON; ++k) {
        if (k >= count) break;
        float phi = step * float(k);
        points[k] = center + circumradius * (cos(phi) * axis_u + sin(phi) * axis_v);
    }
    return count;
}

// A sphere as the disk covering the same cone of directions from shading_point, facing it;
// 0 (no points) inside the sphere: treat the point as surrounded by the light (integral 1).
int ltc_sphere_polygon(vec3 center, float radius, vec3 shading_point, out vec3 points[17], int count) {
    vec3 w = shading_point - center;
    float d = length(w);
    if (!(d > radius)) return 0;
    w = w / d;  // the disk's lit side faces the point: u x v = w
    vec3 u = abs(w.z) < 0.999 ? cross(vec3(0.0, 0.0, 1.0), w) : vec3(1.0, 0.0, 0.0);
    u = normalize(u - w * dot(u, w));
    vec3 v = cross(w, u);
    float disk_radius = radius * d / sqrt((d - radius) * (d + radius));
    return ltc_disk_polygon(center, u, v, disk_radius, points, count);
}
