// The kernels' default short stack (kd_traverse.h's KD_SHORT_STACK_SIZE).
#define KDRAY_STACK_NAMESPACE short_stack
#define KDRAY_STACK_ACCESSOR traversal_short_stack
#include <kdray/traverse.h>  // TraversalArrays, read by traversal_variant.inc

#include "traversal_variant.inc"
