// Where the previous camera saw a hit point, shared by the passes that follow the motion
// (reproject_motion, follow_anchors, taa). The float work is `precise` and in the order of the
// CPU twins (crates/permute/src/reproject.rs project_previous, seen_before), so GPU and CPU pick
// the same pixels. Needs generated/motion.glsl.
#ifndef PROJECT_GLSL
#define PROJECT_GLSL

float dot3(vec3 a, vec3 b) {
    precise float r = a.x * b.x + a.y * b.y + a.z * b.z;
    return r;
}

// The continuous screen position of `position` seen by camera `cam`, and its depth `z` along
// the view direction (not positive: behind the camera).
vec2 project_previous(MotionParams cam, vec3 position, out float z) {
    precise vec3 d = position - cam.cam_origin;
    precise float depth = dot3(d, cam.cam_forward);
    precise float nx = dot3(d, cam.cam_right) / (dot3(cam.cam_right, cam.cam_right) * depth);
    precise float ny = -dot3(d, cam.cam_up) / (dot3(cam.cam_up, cam.cam_up) * depth);
    precise vec2 c = (vec2(nx, ny) + 1.0) * 0.5 * cam.view_size - cam.view_offset;
    z = depth;
    return c;
}

// The pixel `s` that contains `c` (seen at depth `z`), the tie bias putting points on a pixel
// border consistently on one side; false when it is off screen or behind the camera (s is
// then pixel 0: `c` may be NaN or huge).
bool previous_pixel(MotionParams cam, vec2 c, float z, out uvec2 s) {
    precise vec2 biased = c + REPROJECT_TIE_BIAS;
    vec2 f = floor(biased);
    bool inside = z > 0.0 && f.x >= 0.0 && f.y >= 0.0 && f.x < float(cam.width) &&
                  f.y < float(cam.height);
    s = inside ? uvec2(f) : uvec2(0u);
    return inside;
}

#endif
