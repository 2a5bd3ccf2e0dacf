// The block grid of the sorting passes (sort_seeds, classify_pixels): blocks start at
// (k * B - grid) and cover `area` (the screen; the padded screen when the sorting pass also
// retargets), so with a grid offset the blocks at the edges are partial.
// CPU twin: blueshift-permute block_counts / block_pixels. Needs generated/params.glsl.
#ifndef SORT_BLOCKS_GLSL
#define SORT_BLOCKS_GLSL

uint sort_blocks_x(SortParams p, uvec2 area) { return (area.x + p.grid_x + p.block - 1u) / p.block; }

uint sort_block_count(SortParams p, uvec2 area) {
    return sort_blocks_x(p, area) * ((area.y + p.grid_y + p.block - 1u) / p.block);
}

// Top-left corner of block `block` (row-major over the grid); may lie off screen.
ivec2 sort_block_origin(SortParams p, uvec2 area, uint block) {
    uint bx = sort_blocks_x(p, area);
    return ivec2(uvec2(block % bx, block / bx) * p.block) - ivec2(p.grid_x, p.grid_y);
}

#endif
