// A-SVGF's one gradient sample per stratum of frame i [ASVGF18 Sec. 3.3], step 5 of trace/gradients.h: the Vulkan
// port of gradient_winners (trace/gradients.cpp). Of the candidates whose target pixel jbar lies in a stratum of
// frame i, the one with the smallest source index j stays, the first in list order among equal j's. The golden
// function keeps a running minimum per stratum; here every candidate is one invocation, and two dispatches of this
// shader reach the same minimum without a race (push.phase):
//   phase 0 (kGradientMergeMinSource): atomicMin of j into its target stratum's slot of min_source;
//   phase 1 (kGradientMergeWinner):    a candidate whose j is its stratum's minimum atomicMins its own index into
//                                      the stratum's slot of winner (the first in list order).
// Integer work only, so the winners are the golden ones bit for bit, for any order the invocations run in.
//   in:  binding 0 j and 1 jbar (linear index in frame i) per candidate;
//   out: 2 the smallest j per stratum, 3 the winning candidate per stratum (RTDR_INVALID_ID: none; the host fills
//        both with it first). Layout: trace/gradient_merge_shared.h.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "trace/gradient_merge_shared.h"

layout(local_size_x = kGradientMergeGroupSize) in;

RTDR_INPUT_UINT(0, source)
RTDR_INPUT_UINT(1, target)
layout(std430, set = 0, binding = 2) buffer MinSource { uint min_source[]; };
layout(std430, set = 0, binding = 3) buffer Winner { uint winner[]; };

layout(push_constant) uniform Push { GradientMergePush push; };

// GPU only: the push constants, copied once at the top of main() (lavapipe loads a push constant at each use).
GradientMergePush frame;

// The stratum of frame i that target pixel jbar (a linear index) lies in, as a linear index of the stratum grid.
uint target_stratum(uint jbar) {
  const uint x = jbar % frame.width, y = jbar / frame.width;
  const uint s = uint(frame.stratum_size);
  return (y / s) * frame.strata_x + x / s;
}

// gradient_winners [ASVGF18 Sec. 3.3], one candidate k, in two phases.
void main() {
  frame = push;  // the push constants, read once (see above)
  const uint k = gl_GlobalInvocationID.x;  // this invocation's candidate; the last workgroup overhangs the list
  if (k >= frame.candidates) return;
  const uint j = source(int(k)).x;
  if (j == RTDR_INVALID_ID) return;  // no candidate
  const uint stratum = target_stratum(target(int(k)).x);
  if (frame.phase == kGradientMergeMinSource) {
    // The smallest source index j wins the stratum (deterministic, unlike the paper's first-come atomics).
    atomicMin(min_source[stratum], j);
  } else if (min_source[stratum] == j) {
    // Among candidates of that j, the first in list order (in gradient_samples, j's are distinct: one candidate).
    atomicMin(winner[stratum], k);
  }
}
