/* The arguments of kd_trace_closest (kernels/kd_trace.cl), in order, all but the last: one list
 * that the kernel's signature and librender's binder (trace_rays_opencl) both expand, so an
 * argument moved or added here moves on both sides. The batch counter next_ray
 * (__global uint*) follows the list on both sides: a list entry ends in a comma, and a
 * signature cannot. GEOMETRY(type, name) entries are the host's DeviceGeometry::name,
 * BUFFER(type, name) entries other __global buffers, VALUE(type, name) entries are passed by
 * value; type is the device element type. */
#ifndef KD_TRACE_ARGS_H
#define KD_TRACE_ARGS_H

#define KD_TRACE_ARGS(GEOMETRY, BUFFER, VALUE)   \
  GEOMETRY(const KdNode, nodes)                  \
  GEOMETRY(const kd_u32, leaf_blocks)            \
  VALUE(float4, bounds_min)                      \
  VALUE(float4, bounds_max)                      \
  BUFFER(const RayRecord, rays)                  \
  VALUE(uint, ray_count)                         \
  BUFFER(HitRecord, hits)

#endif /* KD_TRACE_ARGS_H */
