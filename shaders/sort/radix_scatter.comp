#version 460
// Radix sort, step 3 of a pass (shaders/shared/radix_sort.h): moves one tile's pairs to their
// places in the output. Thread t holds the consecutive elements t * RADIX_ITEMS + k, so ranking
// in (thread, k) order is ranking in input order. An element's slot in the tile sorted by digit
// is (elements of smaller digits) + (elements of its digit in threads before t) + (elements of
// its digit earlier in its own thread); the last term is a comparison with the thread's own
// elements, the first two are one exclusive prefix sum of the threads' packed counters laid out
// digit-major (counter word w of every thread, then word w + 1: Merrill and Grimshaw 2011,
// "High performance and scalable radix sorting", as in CUB's BlockRadixRank). The sum runs in
// a fixed order on integers: each thread adds a contiguous chunk of RADIX_COUNTER_WORDS entries,
// a Hillis-Steele scan joins the chunk sums. No subgroup operations, no atomics.
//
// The pairs are then reordered by digit in shared memory and written by consecutive threads at
// consecutive slots: each digit's run lands contiguously in the output, so on a GPU the global
// writes coalesce instead of scattering element by element.
#extension GL_GOOGLE_include_directive : require

#include "shared/radix_sort.h"

layout(local_size_x = RADIX_GROUP) in;

layout(std430, binding = 0) readonly buffer KeysIn { uint keysIn[]; };
layout(std430, binding = 1) readonly buffer ValuesIn { uint valuesIn[]; };
layout(std430, binding = 2) readonly buffer Table { uint table[]; };
layout(std430, binding = 3) writeonly buffer KeysOut { uint keysOut[]; };
layout(std430, binding = 4) writeonly buffer ValuesOut { uint valuesOut[]; };
layout(push_constant) uniform Push { RadixSortPush pc; };

// First the packed counters, word w of thread t at [w * RADIX_GROUP + t]; once every thread has
// read its slots, the tile's keys in digit order, then its values.
shared uint scratch[RADIX_COUNTER_WORDS * RADIX_GROUP];
shared uint chunkSums[RADIX_GROUP];
// Output index of the tile's first digit-d element minus its slot in the tile (mod 2^32), so
// that slot s of digit d goes to tileOffset[d] + s.
shared uint tileOffset[RADIX_DIGITS];

uint counterField(uint word, uint digit) {
  return (word >> (RADIX_COUNTER_FIELD(digit) * RADIX_COUNTER_BITS)) & RADIX_COUNTER_MASK;
}

void main() {
  uint t = gl_LocalInvocationID.x;
  uint tile = gl_WorkGroupID.x;
  uint tileBase = tile * RADIX_TILE;
  uint tileSize = min(uint(RADIX_TILE), pc.count - tileBase);
  uint itemCount = min(uint(RADIX_ITEMS), tileSize - min(tileSize, t * RADIX_ITEMS));

  uint keys[RADIX_ITEMS];
  uint digits[RADIX_ITEMS];
  uint before[RADIX_ITEMS];  // earlier elements of the same digit in this thread
  uint words[RADIX_COUNTER_WORDS];
  for (uint w = 0u; w < RADIX_COUNTER_WORDS; ++w) words[w] = 0u;
  for (uint k = 0u; k < RADIX_ITEMS; ++k) {
    keys[k] = 0u;
    if (k < itemCount) keys[k] = keysIn[tileBase + t * RADIX_ITEMS + k];
    digits[k] = (keys[k] >> pc.shift) & RADIX_DIGIT_MASK;
    before[k] = 0u;
    for (uint j = 0u; j < k; ++j) before[k] += digits[j] == digits[k] ? 1u : 0u;
    // Constant word indices (a select per word) keep `words` in registers.
    uint one = k < itemCount ? 1u << (RADIX_COUNTER_FIELD(digits[k]) * RADIX_COUNTER_BITS) : 0u;
    for (uint w = 0u; w < RADIX_COUNTER_WORDS; ++w)
      words[w] += RADIX_COUNTER_WORD(digits[k]) == w ? one : 0u;
  }
  for (uint w = 0u; w < RADIX_COUNTER_WORDS; ++w) scratch[w * RADIX_GROUP + t] = words[w];
  barrier();

  // Exclusive scan of the counters in index order (digit-major). Fields never carry into each
  // other: no sum exceeds the tile's RADIX_TILE < 2^16 elements.
  uint chunk[RADIX_COUNTER_WORDS];
  uint sum = 0u;
  for (uint j = 0u; j < RADIX_COUNTER_WORDS; ++j) {
    chunk[j] = scratch[t * RADIX_COUNTER_WORDS + j];
    sum += chunk[j];
  }
  chunkSums[t] = sum;
  barrier();
  for (uint offset = 1u; offset < RADIX_GROUP; offset <<= 1u) {
    uint add = t >= offset ? chunkSums[t - offset] : 0u;
    barrier();
    chunkSums[t] += add;
    barrier();
  }
  uint running = t > 0u ? chunkSums[t - 1u] : 0u;
  for (uint j = 0u; j < RADIX_COUNTER_WORDS; ++j) {
    scratch[t * RADIX_COUNTER_WORDS + j] = running;
    running += chunk[j];
  }
  // The scan ranks the low fields (digits 0-7) and the high fields (8-15) separately; the high
  // digits come after all the low ones, whose count is the low field of the grand total.
  uint lowTotal = chunkSums[RADIX_GROUP - 1] & RADIX_COUNTER_MASK;
  barrier();

  uint slots[RADIX_ITEMS];
  for (uint k = 0u; k < RADIX_ITEMS; ++k) {
    uint word = scratch[RADIX_COUNTER_WORD(digits[k]) * RADIX_GROUP + t];
    slots[k] = counterField(word, digits[k]) + before[k] +
               (RADIX_COUNTER_FIELD(digits[k]) == 1u ? lowTotal : 0u);
  }
  if (t < RADIX_DIGITS) {
    uint firstSlot = counterField(scratch[RADIX_COUNTER_WORD(t) * RADIX_GROUP], t) +
                     (RADIX_COUNTER_FIELD(t) == 1u ? lowTotal : 0u);
    tileOffset[t] = table[t * pc.tileCount + tile] - firstSlot;
  }
  barrier();  // every counter read, so `scratch` can take the keys

  // Keys, then values, go through `scratch` in digit order (one tile of words fits where the
  // counters were, within the 16 KiB of shared memory every device has).
  for (uint k = 0u; k < RADIX_ITEMS; ++k)
    if (k < itemCount) scratch[slots[k]] = keys[k];
  barrier();
  uint dst[RADIX_ITEMS];
  for (uint k = 0u; k < RADIX_ITEMS; ++k) {
    uint slot = k * RADIX_GROUP + t;
    if (slot < tileSize) {
      uint key = scratch[slot];
      dst[k] = tileOffset[(key >> pc.shift) & RADIX_DIGIT_MASK] + slot;
      keysOut[dst[k]] = key;
    }
  }
  barrier();
  for (uint k = 0u; k < RADIX_ITEMS; ++k)
    if (k < itemCount) scratch[slots[k]] = valuesIn[tileBase + t * RADIX_ITEMS + k];
  barrier();
  for (uint k = 0u; k < RADIX_ITEMS; ++k) {
    uint slot = k * RADIX_GROUP + t;
    if (slot < tileSize) valuesOut[dst[k]] = scratch[slot];
  }
}
