// Stable LSD radix sort of (uint key, uint value) pairs (engine/include/engine/radix_sort.h), 4-bit
// digits, one pass per digit from the lowest, three dispatches per pass:
//
//   radix_histogram.comp  one group per tile of RADIX_TILE consecutive elements: the tile's 16
//                         digit counts into the table, digit-major: table[d * tileCount + tile]
//   radix_scan.comp       ONE group: exclusive prefix sum of the table in index order, so
//                         table[d * tileCount + tile] = where the tile's first digit-d element
//                         goes (every smaller digit, then digit d of every earlier tile)
//   radix_scatter.comp    one group per tile: each element's rank among the tile's elements of
//                         its digit, in input order, and the pair written to table + rank
//
// Ranks keep input order inside a tile and the table keeps tile order, so every pass is stable
// and LSD passes compose into a sort by the whole key. Offsets and ranks are integer sums in a
// fixed order (the histogram's shared atomics only count, and a count does not depend on the
// order of its additions): the output is the one stable order, bit-identical on every run.
#ifndef SHADERS_SHARED_RADIX_SORT_H
#define SHADERS_SHARED_RADIX_SORT_H
#include "interop.h"

#define RADIX_DIGIT_BITS 4
#define RADIX_DIGITS 16  // 2^RADIX_DIGIT_BITS
#define RADIX_DIGIT_MASK 15u
// 8 elements per thread measured ~25 % fewer instructions per element than 4 on lavapipe (the
// per-thread counter scan is shared by more elements); the scatter's shared memory, one tile of
// words, stays at 8 KiB.
#define RADIX_GROUP 256       // threads per group of the histogram and scatter passes
#define RADIX_ITEMS 8         // elements per thread of those passes
#define RADIX_TILE 2048       // RADIX_GROUP * RADIX_ITEMS elements per tile (one group's share)
#define RADIX_SCAN_GROUP 256  // threads of the single scan group
// Per-thread digit counts are packed two to a uint, 16 bits each (a tile's 2048 elements never
// overflow one): digit d lives in word d % 8 at field d / 8, so that a prefix sum of the words in
// digit-major order ranks digits 0-7 in the low fields and 8-15 in the high ones at once.
#define RADIX_COUNTER_WORDS 8
#define RADIX_COUNTER_WORD(digit) ((digit)&7u)
#define RADIX_COUNTER_FIELD(digit) ((digit) >> 3u)
#define RADIX_COUNTER_BITS 16u
#define RADIX_COUNTER_MASK 0xFFFFu

SHARED_BEGIN

struct RadixSortPush {
  uint count;      // pairs being sorted
  uint shift;      // bit of this pass's digit: 0, 4, 8, ...
  uint tileCount;  // ceil(count / RADIX_TILE): groups of the histogram and scatter passes
  uint pad0;
};

SHARED_END

SHARED_ASSERT_SIZE(RadixSortPush, 16);
#ifdef __cplusplus
static_assert(RADIX_TILE == RADIX_GROUP * RADIX_ITEMS, "a tile is one group's elements");
static_assert(RADIX_TILE < (1 << 16), "packed per-thread counters hold 16 bits");
static_assert(RADIX_COUNTER_WORDS * 2 == RADIX_DIGITS, "two counters per word");
// radix_scatter.comp reuses the counters' shared memory for the tile's keys, then its values.
static_assert(RADIX_COUNTER_WORDS * RADIX_GROUP >= RADIX_TILE, "scatter's shared reuse");
#endif
#endif
