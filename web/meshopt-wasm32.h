/* Forced into meshoptimizer's C++ when it is compiled for wasm32 (scripts/web.sh sets
 * CFLAGS_wasm32_unknown_unknown): the meshopt crate's stripped-down wasm32 <math.h> lacks functions
 * that meshoptimizer's newer files call (opacity maps, quantization, tangent spaces). All are
 * compiler built-ins; none of that code is linked into Chamfer, which uses only the vertex and
 * index encoders. */
#define floorf __builtin_floorf
#define ceilf __builtin_ceilf
#define cosf __builtin_cosf
#define log2f __builtin_log2f
#define frexpf __builtin_frexpf
#define ldexpf __builtin_ldexpf
