#version 450
/* The example host's mesh: world-space triangles, one view-projection matrix. */
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in float albedo;
layout(push_constant) uniform Push { mat4 view_proj; vec4 sun_dir; vec4 sun_illuminance; } push;
layout(location = 0) out vec3 v_normal;
layout(location = 1) out float v_albedo;
void main()
{
    gl_Position = push.view_proj * vec4(position, 1.0);
    v_normal = normal;
    v_albedo = albedo;
}
