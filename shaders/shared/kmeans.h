// The k-means clustering baseline (vsgl-math.md section 9): feature spaces, weightings and the
// push constants of the kmeans_*.comp passes. One iteration is
//   kmeans_assign  (every powered texel -> nearest centre, cluster counts, costliest member)
//   kmeans_fill    (empty clusters take the costliest member of a donor cluster)
//   radix sort     ((cluster, texel) pairs by cluster, engine::RadixSort)
//   kmeans_bounds  (each cluster's range in the sorted pairs)
//   kmeans_sum     (per cluster: attribute sums -> VSGL, weighted mean -> new centre)
// after kmeans_seed (fresh centres) or the previous frame's centres.
#ifndef SHADERS_SHARED_KMEANS_H
#define SHADERS_SHARED_KMEANS_H
#include "interop.h"

#define KMEANS_SPACE_IMAGE 0u  // features: texel centres in [0, 1]^2 of the RSM
#define KMEANS_SPACE_WORLD 1u  // features: VPL positions relative to the RSM origin, m

#define KMEANS_WEIGHT_PDF 0u      // centres and cost weighted by the PDF (view-dependent with BRSM)
#define KMEANS_WEIGHT_UNIFORM 1u  // every powered texel weighs 1

// An unpowered texel belongs to no cluster: its key is K, which sorts after every cluster and
// keeps the keys within bit_width(K) bits for the radix sort.
#define KMEANS_SEED_GROUP 64
#define KMEANS_ASSIGN_GROUP 64
#define KMEANS_ASSIGN_TEXELS 16  // texels per assign thread (kmeans_assign.comp says why)
#define KMEANS_FILL_GROUP 256
#define KMEANS_BOUNDS_GROUP 256
#define KMEANS_SUM_GROUP 64  // threads summing one cluster

SHARED_BEGIN

struct KmeansPush {
  vec4 origin;      // xyz = RSM origin (world), added to every VSGL mean
  uint clusters;    // K
  uint size;        // attribute pyramid base size (power of two)
  uint topLevel;    // log2(size)
  uint space;       // KMEANS_SPACE_*
  uint weighting;   // KMEANS_WEIGHT_*
  uint texelCount;  // size * size
  uint iteration;   // index of the current iteration (where kmeans_fill writes its count)
  uint pad1;
};

SHARED_END

SHARED_ASSERT_SIZE(KmeansPush, 48);
#endif
