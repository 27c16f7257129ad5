// A stack as deep as any tree may be: never overflows, never restarts.
#define KD_SHORT_STACK_SIZE 64
#define KDRAY_STACK_NAMESPACE full_stack
#define KDRAY_STACK_ACCESSOR traversal_full_stack
#include <kdray/traverse.h>  // TraversalArrays, read by traversal_variant.inc

#include "traversal_variant.inc"
static_assert(KD_SHORT_STACK_SIZE == KD_MAX_TREE_DEPTH, "the full stack holds one entry per level");
