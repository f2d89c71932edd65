// The threads of a dispatch (host-sim/src/gpu/shaders.rs, DISPATCH).
//
// A kernel runs WORKGROUP threads per workgroup over a 2D grid of workgroups (one dimension
// holds at most 65,535 of them, 4.2 million threads); thread_index numbers the threads 0, 1, ...
// row by row, so thread i serves element i whatever the grid's shape.

const WORKGROUP: u32 = 64u;

fn thread_index(id: vec3<u32>, groups: vec3<u32>) -> u32 {
    return id.x + id.y * groups.x * WORKGROUP;
}
