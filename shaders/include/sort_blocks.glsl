// The block grid of the sorting passes (sort_seeds, classify_pixels): blocks start at
// (k * B - grid), so with a grid offset the blocks at the screen edges are partial.
// CPU twin: blueshift-permute block_counts / block_pixels. Needs generated/params.glsl.
#ifndef SORT_BLOCKS_GLSL
#define SORT_BLOCKS_GLSL

uint sort_blocks_x(SortParams p) { return (p.width + p.grid_x + p.block - 1u) / p.block; }

uint sort_block_count(SortParams p) {
    return sort_blocks_x(p) * ((p.height + p.grid_y + p.block - 1u) / p.block);
}

// Top-left corner of block `block` (row-major over the grid); may lie off screen.
ivec2 sort_block_origin(SortParams p, uint block) {
    uint bx = sort_blocks_x(p);
    return ivec2(uvec2(block % bx, block / bx) * p.block) - ivec2(p.grid_x, p.grid_y);
}

// Pixel `k` (row-major, k < B*B) of the block at `origin`; false when it is off screen.
bool sort_block_pixel(SortParams p, ivec2 origin, uint k, out uvec2 px) {
    ivec2 q = origin + ivec2(k % p.block, k / p.block);
    px = uvec2(max(q, ivec2(0)));
    return q.x >= 0 && q.y >= 0 && q.x < int(p.width) && q.y < int(p.height);
}

#endif
