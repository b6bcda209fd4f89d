{{HEADER}}
#version 450 core

// The tiles of pixels whose candidate lists the fragment stage runs: one
// point a tile, as wide as the tile.
{{UNIFORM_LIST_TILE}}
{{TEXTURE_LIST_TILES}}

void main()
{
    uint tile = texelFetch(sc_list_tiles, sc_list_tile.x + gl_VertexID).r;
    vec2 centre = vec2(float(tile & 0xffffu), float(tile >> 16)) + 0.5 * float(sc_list_tile.w);
    gl_Position = vec4(2.0 * centre / vec2(sc_list_tile.yz) - 1.0, 0.0, 1.0);
    gl_PointSize = float(sc_list_tile.w);
}
