// zshift: Kooima's median-distance perspective projection ("Median Distance Perspective
// Projection", seed 003), with a depth offset. Include this function in a vertex shader.
//
// Convention: OpenGL right-handed eye space looking down -z, NDC depth [-1, 1]
// (glClipControl default), glDepthRange(0, 1), depth test GL_LESS. NDC depth is
// (d - median)/(d + median) at eye distance d = -eye.z: -1 at the eye, 0 at the median,
// -> 1 at infinity; x and y are those of `projection` (near/far of it have no effect on depth).
//
// ndc_offset is added to NDC depth (negative moves toward the camera): zshift computes it for
// an eye-space shift delta at Pz with zshift_median_ndc_offset (Rust: median::ndc_offset).
// ndc_offset = 0 gives Kooima's ftransform_mdp exactly. In the compatibility profile pass
// gl_ProjectionMatrix and gl_ModelViewMatrix * gl_Vertex.
// Geometry at the eye (eye.z == 0) divides by zero, as in the original: cull it.
vec4 zshift_ftransform_mdp(mat4 projection, vec4 eye, float median, float ndc_offset)
{
    vec4 clip;
    clip.xy = -(projection * eye).xy * (-eye.z + median) / eye.z;
    clip.w  = -eye.z + median;
    clip.z  = (-eye.z - median) + ndc_offset * clip.w;
    return clip;
}
