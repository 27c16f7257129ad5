// A one-entry stack: every second push overflows, so restarts are exercised constantly.
#define KD_SHORT_STACK_SIZE 1
#define KDRAY_STACK_NAMESPACE depth1_stack
#define KDRAY_STACK_ACCESSOR traversal_depth1_stack
#include "traversal_variant.inc"
