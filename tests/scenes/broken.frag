#version 450 core
// Test shader with a deliberate error on line 7.
in vec2 v_uv;
out vec4 o_color;
void main()
{
    o_color = vec4(no_such_thing, 1.0);
}
