// A one-entry stack: every second push overflows, so restarts are exercised constantly.
#define KD_SHORT_STACK_SIZE 1
#define KDRAY_STACK_NAMESPACE depth1_stack
#define KDRAY_STACK_ACCESSOR traversal_depth1_stack
#include <kdray/traverse.h>  // TraversalArrays, read by traversal_variant.inc

#include "traversal_variant.inc"
