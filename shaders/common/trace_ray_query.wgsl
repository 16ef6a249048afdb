// The ray-query backend of trace.wgsl: the driver's acceleration structures
// (render/src/gpu_scene/accel.rs: one BLAS for the static scene, one per distinct moving
// mesh in its node's space, a TLAS of their instances per frame, last frame's kept) walked
// by the hardware. Triangles of materials without alpha test or transparency are OPAQUE
// geometry, committed by the hardware without asking; every other candidate comes back
// here and goes through the same hit rules as the software backend.

// The scene slot (BVH order, the index of `triangles`) of a candidate or committed hit:
// accel_map holds per instance (first entry of its slots, opaque primitives) and then the
// slots of each BLAS's primitives, opaque geometry first.
fn ray_query_triangle(hit: RayIntersection) -> u32 {
    let instance = hit.instance_custom_data;
    let first = accel_map[2u * instance];
    let opaque = accel_map[2u * instance + 1u];
#ifdef PLANTED_RAY_QUERY_NO_GEOMETRY_OFFSET
    // Test only (render/tests/ray_backends.rs): tested geometry's primitives read as the
    // opaque geometry's.
    return accel_map[first + hit.primitive_index];
#else
    return accel_map[first + select(0u, opaque, hit.geometry_index == 1u) + hit.primitive_index];
#endif
}

fn trace(ray: Ray, mode: u32, cull_single_sided_back: bool, geometry: u32, transmittance: ptr<function, Transmittance>) -> Hit {
    // Culling is per material, so a culling ray sees opaque geometry as candidates too.
#ifdef PLANTED_RAY_QUERY_NO_CULLING
    var flags = RAY_FLAG_NONE;  // test only (render/tests/ray_backends.rs)
#else
    var flags = select(RAY_FLAG_NONE, RAY_FLAG_FORCE_NO_OPAQUE, cull_single_sided_back);
#endif
    if mode != TRACE_CLOSEST {
        // An opaque hit ends a shadow ray: nothing gets through it.
        flags |= RAY_FLAG_TERMINATE_ON_FIRST_HIT;
    }
    let desc = RayDesc(flags, 0xffu, 0.0, ray.t_max, ray.origin, ray.dir);
    var rq: ray_query;
#ifdef ANIMATION
    if geometry == GEOMETRY_PREVIOUS {
        rayQueryInitialize(&rq, prev_scene_tlas, desc);
    } else {
        rayQueryInitialize(&rq, scene_tlas, desc);
    }
#else
    rayQueryInitialize(&rq, scene_tlas, desc);
#endif
    var state = trace_state(ray);
    var stopped = false;
    while rayQueryProceed(&rq) {
        let c = rayQueryGetCandidateIntersection(&rq);
        if c.kind != RAY_QUERY_INTERSECTION_TRIANGLE || !(c.t < state.t_max) {
            continue;
        }
        let tri_index = ray_query_triangle(c);
        let tri = geometry_triangle(tri_index, geometry);
        if !hit_is_accepted(tri_index, tri, c.barycentrics.x, c.barycentrics.y, ray, cull_single_sided_back) {
            continue;
        }
        let action = take_hit(&state, mode, tri_index, vec3<f32>(c.t, c.barycentrics), ray.dir, transmittance);
        if action == HIT_CLOSER {
            rayQueryConfirmIntersection(&rq);
        } else if action == HIT_STOP {
            stopped = true;
            rayQueryTerminate(&rq);
        }
    }
    if stopped {
        return state.best;
    }
    // The nearest opaque hit the hardware committed, or the nearest confirmed candidate.
    let committed = rayQueryGetCommittedIntersection(&rq);
    if committed.kind == RAY_QUERY_INTERSECTION_TRIANGLE {
        if mode != TRACE_CLOSEST {
            (*transmittance).value = vec3<f32>(0.0);
        }
        return Hit(committed.t, ray_query_triangle(committed), committed.barycentrics.x, committed.barycentrics.y);
    }
    // Nothing opaque: a shadow ray that crossed only layers reports the last one.
    return state.best;
}
