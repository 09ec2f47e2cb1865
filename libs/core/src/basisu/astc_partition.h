#pragma once
// ASTC's partition pattern generation (Khronos Data Format Specification, "Partition Pattern
// Generation"), for 2D blocks: which partition (subset) texel (x, y) of a block belongs to. Shared
// by the UASTC decoder (its 2- and 3-subset patterns are ASTC seeds) and the ASTC HDR decoder.
#include <cstdint>

namespace fresnel::basisu {

constexpr std::uint32_t astc_partition_hash(std::uint32_t p) {
    p ^= p >> 15;
    p -= p << 17;
    p += p << 7;
    p += p << 4;
    p ^= p >> 5;
    p += p << 16;
    p ^= p >> 7;
    p ^= p >> 3;
    p ^= p << 6;
    p ^= p >> 17;
    return p;
}

// The partition (0 .. partitions-1) of texel (x, y) for `seed` (10 bits) and `partitions` (1..4);
// `small_block`: the block has fewer than 31 texels (a 4x4 block: coordinates doubled).
constexpr int astc_select_partition(int seed, int x, int y, int partitions, bool small_block) {
    if (small_block) x <<= 1, y <<= 1;
    seed += (partitions - 1) * 1024;
    const std::uint32_t rnum = astc_partition_hash(std::uint32_t(seed));
    int s[8] = {};
    for (int i = 0; i < 8; ++i) s[i] = int((rnum >> (4 * i)) & 0xF), s[i] *= s[i];
    int sh1 = 0, sh2 = 0;
    if (seed & 1) sh1 = (seed & 2) ? 4 : 5, sh2 = partitions == 3 ? 6 : 5;
    else sh1 = partitions == 3 ? 6 : 5, sh2 = (seed & 2) ? 4 : 5;
    for (int i = 0; i < 8; ++i) s[i] >>= (i & 1) ? sh2 : sh1;
    // seed9..seed12 multiply z, which is 0 in 2D.
    int a = (s[0] * x + s[1] * y + int(rnum >> 14)) & 0x3F;
    int b = (s[2] * x + s[3] * y + int(rnum >> 10)) & 0x3F;
    int c = (s[4] * x + s[5] * y + int(rnum >> 6)) & 0x3F;
    int d = (s[6] * x + s[7] * y + int(rnum >> 2)) & 0x3F;
    if (partitions < 4) d = 0;
    if (partitions < 3) c = 0;
    if (a >= b && a >= c && a >= d) return 0;
    if (b >= c && b >= d) return 1;
    if (c >= d) return 2;
    return 3;
}

}  // namespace fresnel::basisu
