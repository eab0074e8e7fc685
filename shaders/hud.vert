// HUD text and panels in pixel coordinates, origin top-left.
layout(location = 0) in vec2 aPos;
uniform vec2 uViewport;
void main() { gl_Position = vec4(aPos.x / uViewport.x * 2.0 - 1.0, 1.0 - aPos.y / uViewport.y * 2.0, 0.0, 1.0); }
