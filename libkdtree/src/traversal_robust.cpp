// The robust traversal alone (KD_TRAVERSAL_ROBUST_ONLY) with the kernels' short stack: what
// every ray ran before the fast path, for comparing the two (TraversalPath::Robust).
#define KD_TRAVERSAL_ROBUST_ONLY
#define KDRAY_STACK_NAMESPACE robust_short_stack
#define KDRAY_STACK_ACCESSOR traversal_robust_short_stack
#include <kdray/traverse.h>  // TraversalArrays, read by traversal_variant.inc

#include "traversal_variant.inc"
