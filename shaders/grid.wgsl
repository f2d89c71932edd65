// The neighbour grid on the GPU (host-sim/src/gpu/shaders.rs, GRID; driven by
// host-sim/src/gpu/grid.rs): agents sorted by a precomputed cell key, the structure of the CPU
// grid's counting sort (host-sim/src/grid.rs) in the same order.
//
// Output: starts[c]..starts[c + 1] are the slots of cell c (n_cells + 1 entries, the exclusive
// prefix sum of the cell counts) and order[slot] the agent in that slot, sorted by (cell, agent
// index): exactly what a stable counting sort gives, whatever the scheduling.
//
// The kernels:
//
// * grid_count: one thread per agent, atomicAdd into the per-cell counters (starts, cleared
//   first). Additions commute, so the counts do not depend on the order the atomics land in.
// * grid_scan_blocks / grid_scan_add: an exclusive prefix sum in place, in blocks of
//   GRID_SCAN_BLOCK = 1024 elements (a workgroup of WORKGROUP = 64 threads, 16 elements each):
//   each block is scanned in workgroup memory and its total written to the next level, which is
//   scanned the same way (1024 times shorter: 16M cells take three levels), then every level
//   below the top gets the scanned totals of the level above added back. Used for starts and for
//   the radix histograms.
// * grid_radix_count / grid_radix_scatter: order comes from a stable least-significant-digit
//   radix sort of the (cell, agent) pairs by cell, GRID_RADIX_BITS = 6 bits a pass
//   (ceil(log2(n_cells) / 6) passes, at least one: 1 up to 64 cells, 4 up to 16M cells). A pass
//   cuts the agents into blocks of GRID_RADIX_BLOCK = 2048 (a workgroup, 32 consecutive agents
//   per thread). grid_radix_count counts each block's digits into hist[digit * blocks + block];
//   the scan turns that digit-major table into the first output slot of each (digit, block);
//   grid_radix_scatter then gives every agent its slot without atomics: each thread counts its
//   own 32 agents per digit in workgroup memory, one thread per digit turns its digit's counts
//   into slots thread by thread, and each thread writes its agents in order. Within a digit the
//   agents keep their order (block, then thread, then place in the thread's run), so the pass is
//   stable, and every slot is a function of the keys alone.
//
// Why a radix sort, and not a plain counting sort's atomic scatter followed by a sort of each
// cell's slice by agent index (one thread per cell): the atomic scatter's order within a cell
// depends on which thread reached the cell's cursor first, so that fix-up sort is needed, and it
// is serial work on the most crowded cell, O(k log k) on one thread for a cell of k agents.
// Swarms crowd (every ant starts at its nest). On a GPU a heap sort of 100,000 agents in one
// thread is millions of dependent memory accesses, milliseconds to tenths of a second while the
// rest of the GPU idles; and on lavapipe (Mesa 22.3, the test GPU) it is not even correct:
// gallivm stops a loop after 65,535 iterations in one invocation (an inner loop's iterations
// add up over the outer one's), so such a sort stops half-way, silently (measured: a heap sort
// of 20,000 agents in one cell came back a heap). The radix sort does the same work for any
// distribution of agents over cells (a few reads and two writes per agent and pass, no
// atomics), and no invocation here runs more than 200 loop iterations. Its
// price is one pass per 6 bits of the cell index: for a million agents over a million cells on
// lavapipe (2 cores) the whole grid takes about 165 ms of CPU time, where the atomic scatter
// with per-cell sort would take about 95 ms (measured with a throwaway kernel, correct there
// only because no cell was crowded).
//
// Keys at or above n_cells are read as n_cells - 1 (the last cell), by the count and the sort
// alike, so starts and order always agree and no write leaves its buffer.

const GRID_SCAN_PER_THREAD: u32 = 16u;
const GRID_SCAN_BLOCK: u32 = 1024u;
const GRID_RADIX_BITS: u32 = 6u;
const GRID_RADIX: u32 = 64u;
const GRID_KEYS_PER_THREAD: u32 = 32u;
const GRID_RADIX_BLOCK: u32 = 2048u;
const_assert GRID_RADIX == WORKGROUP;
const_assert GRID_RADIX == 1u << GRID_RADIX_BITS;
const_assert GRID_SCAN_BLOCK == WORKGROUP * GRID_SCAN_PER_THREAD;
const_assert GRID_RADIX_BLOCK == WORKGROUP * GRID_KEYS_PER_THREAD;

// grid_radix_scatter flags: the values in are the agent indices (the first pass reads no
// values); the keys are written out (every pass but the last).
const GRID_VALS_ARE_INDICES: u32 = 1u;
const GRID_WRITE_KEYS: u32 = 2u;

// The parameters of one dispatch (GridParams in grid.rs).
struct GridParams {
    // Elements: agents (count, radix), or the length of the array scanned.
    len: u32,
    // The largest valid key, n_cells - 1.
    last: u32,
    // The radix pass's digit: (key >> shift) & (GRID_RADIX - 1).
    shift: u32,
    // Radix blocks of this sort: ceil(len / GRID_RADIX_BLOCK).
    blocks: u32,
    // GRID_VALS_ARE_INDICES | GRID_WRITE_KEYS.
    flags: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

// The workgroup's index in a 2D grid of workgroups (uniform, so barriers may follow it).
fn grid_block(wid: vec3<u32>, groups: vec3<u32>) -> u32 {
    return wid.x + wid.y * groups.x;
}

// ---- count ----

@group(0) @binding(0) var<uniform> grid_count_params: GridParams;
@group(0) @binding(1) var<storage, read> grid_count_cells: array<u32>;
@group(0) @binding(2) var<storage, read_write> grid_count_counts: array<atomic<u32>>;

@compute @workgroup_size(WORKGROUP)
fn grid_count(@builtin(global_invocation_id) id: vec3<u32>,
              @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i >= grid_count_params.len) {
        return;
    }
    let c = min(grid_count_cells[i], grid_count_params.last);
    atomicAdd(&grid_count_counts[c], 1u);
}

// ---- exclusive scan ----

@group(0) @binding(0) var<uniform> grid_scan_params: GridParams;
@group(0) @binding(1) var<storage, read_write> grid_scan_data: array<u32>;
@group(0) @binding(2) var<storage, read_write> grid_scan_sums: array<u32>;

// One block, one padding word per 32 so that the threads' serial runs of 16 fall in different
// banks.
var<workgroup> grid_scan_tile: array<u32, 1056>;
var<workgroup> grid_scan_part: array<u32, WORKGROUP>;

fn grid_scan_pad(j: u32) -> u32 {
    return j + (j >> 5u);
}

// Scans each block of GRID_SCAN_BLOCK elements of data in place (exclusive) and writes the
// block's total to sums[block].
@compute @workgroup_size(WORKGROUP)
fn grid_scan_blocks(@builtin(local_invocation_index) lid: u32,
                    @builtin(workgroup_id) wid: vec3<u32>,
                    @builtin(num_workgroups) groups: vec3<u32>) {
    let block = grid_block(wid, groups);
    let len = grid_scan_params.len;
    if (block * GRID_SCAN_BLOCK >= len) {
        return;
    }
    let base = block * GRID_SCAN_BLOCK;
    // Coalesced loads: thread t takes elements t, t + 64, ...
    for (var k = 0u; k < GRID_SCAN_PER_THREAD; k++) {
        let j = k * WORKGROUP + lid;
        var v = 0u;
        if (base + j < len) {
            v = grid_scan_data[base + j];
        }
        grid_scan_tile[grid_scan_pad(j)] = v;
    }
    workgroupBarrier();
    // Thread t scans elements 16t .. 16t + 15 serially.
    var sum = 0u;
    for (var k = 0u; k < GRID_SCAN_PER_THREAD; k++) {
        let j = grid_scan_pad(lid * GRID_SCAN_PER_THREAD + k);
        let v = grid_scan_tile[j];
        grid_scan_tile[j] = sum;
        sum += v;
    }
    grid_scan_part[lid] = sum;
    workgroupBarrier();
    // Inclusive scan of the threads' totals (Hillis-Steele).
    for (var d = 1u; d < WORKGROUP; d = d << 1u) {
        var v = 0u;
        if (lid >= d) {
            v = grid_scan_part[lid - d];
        }
        workgroupBarrier();
        grid_scan_part[lid] += v;
        workgroupBarrier();
    }
    let before = grid_scan_part[lid] - sum;
    for (var k = 0u; k < GRID_SCAN_PER_THREAD; k++) {
        let j = grid_scan_pad(lid * GRID_SCAN_PER_THREAD + k);
        grid_scan_tile[j] += before;
    }
    if (lid == WORKGROUP - 1u) {
        grid_scan_sums[block] = grid_scan_part[lid];
    }
    workgroupBarrier();
    for (var k = 0u; k < GRID_SCAN_PER_THREAD; k++) {
        let j = k * WORKGROUP + lid;
        if (base + j < len) {
            grid_scan_data[base + j] = grid_scan_tile[grid_scan_pad(j)];
        }
    }
}

// Adds to each element of data the scanned total of the blocks before its block.
@compute @workgroup_size(WORKGROUP)
fn grid_scan_add(@builtin(global_invocation_id) id: vec3<u32>,
                 @builtin(num_workgroups) groups: vec3<u32>) {
    let i = thread_index(id, groups);
    if (i < GRID_SCAN_BLOCK || i >= grid_scan_params.len) {
        return;
    }
    grid_scan_data[i] += grid_scan_sums[i / GRID_SCAN_BLOCK];
}

// ---- radix sort ----

fn grid_digit(key: u32, p: GridParams) -> u32 {
    return (min(key, p.last) >> p.shift) & (GRID_RADIX - 1u);
}

@group(0) @binding(0) var<uniform> grid_hist_params: GridParams;
@group(0) @binding(1) var<storage, read> grid_hist_keys: array<u32>;
@group(0) @binding(2) var<storage, read_write> grid_hist: array<u32>;

var<workgroup> grid_hist_counts: array<atomic<u32>, GRID_RADIX>;

// hist[d * blocks + block] = the agents of the block whose digit is d.
@compute @workgroup_size(WORKGROUP)
fn grid_radix_count(@builtin(local_invocation_index) lid: u32,
                    @builtin(workgroup_id) wid: vec3<u32>,
                    @builtin(num_workgroups) groups: vec3<u32>) {
    let p = grid_hist_params;
    let block = grid_block(wid, groups);
    if (block >= p.blocks) {
        return;
    }
    atomicStore(&grid_hist_counts[lid], 0u);
    workgroupBarrier();
    let base = block * GRID_RADIX_BLOCK;
    // Counting is order-free: coalesced loads.
    for (var k = 0u; k < GRID_KEYS_PER_THREAD; k++) {
        let i = base + k * WORKGROUP + lid;
        if (i < p.len) {
            atomicAdd(&grid_hist_counts[grid_digit(grid_hist_keys[i], p)], 1u);
        }
    }
    workgroupBarrier();
    grid_hist[lid * p.blocks + block] = atomicLoad(&grid_hist_counts[lid]);
}

@group(0) @binding(0) var<uniform> grid_sort_params: GridParams;
@group(0) @binding(1) var<storage, read> grid_sort_keys_in: array<u32>;
@group(0) @binding(2) var<storage, read> grid_sort_vals_in: array<u32>;
@group(0) @binding(3) var<storage, read> grid_sort_hist: array<u32>;
@group(0) @binding(4) var<storage, read_write> grid_sort_keys_out: array<u32>;
@group(0) @binding(5) var<storage, read_write> grid_sort_vals_out: array<u32>;

// Per (digit, thread): first the thread's count of its agents with that digit, then the slot of
// its next such agent. 64 x 64 words, 16 KiB: WebGPU's default workgroup memory limit.
var<workgroup> grid_sort_slots: array<u32, 4096>;

// The word of (digit d, thread t), skewed so that a thread walking its digits and a digit's
// thread walking the threads both touch 64 different banks at each step.
fn grid_slot(d: u32, t: u32) -> u32 {
    return d * GRID_RADIX + ((t + d) & (GRID_RADIX - 1u));
}

// Moves each agent of the block to its slot: hist (scanned) gives the first slot of each
// (digit, block), and within a block the agents of one digit keep their order, as the thread
// that holds them and their place in its run of 32 give it. A stable pass, without atomics.
@compute @workgroup_size(WORKGROUP)
fn grid_radix_scatter(@builtin(local_invocation_index) lid: u32,
                      @builtin(workgroup_id) wid: vec3<u32>,
                      @builtin(num_workgroups) groups: vec3<u32>) {
    let p = grid_sort_params;
    let block = grid_block(wid, groups);
    if (block >= p.blocks) {
        return;
    }
    for (var d = 0u; d < GRID_RADIX; d++) {
        grid_sort_slots[grid_slot(d, lid)] = 0u;
    }
    // Thread t holds the block's agents 32t .. 32t + 31, in order.
    let first = block * GRID_RADIX_BLOCK + lid * GRID_KEYS_PER_THREAD;
    var keys: array<u32, GRID_KEYS_PER_THREAD>;
    for (var k = 0u; k < GRID_KEYS_PER_THREAD; k++) {
        let i = first + k;
        if (i < p.len) {
            keys[k] = min(grid_sort_keys_in[i], p.last);
            grid_sort_slots[grid_slot(grid_digit(keys[k], p), lid)] += 1u;
        }
    }
    workgroupBarrier();
    // Thread d turns digit d's counts into slots, thread by thread.
    var slot = grid_sort_hist[lid * p.blocks + block];
    for (var t = 0u; t < WORKGROUP; t++) {
        let s = grid_slot(lid, t);
        let count = grid_sort_slots[s];
        grid_sort_slots[s] = slot;
        slot += count;
    }
    workgroupBarrier();
    for (var k = 0u; k < GRID_KEYS_PER_THREAD; k++) {
        let i = first + k;
        if (i < p.len) {
            let s = grid_slot(grid_digit(keys[k], p), lid);
            let dst = grid_sort_slots[s];
            grid_sort_slots[s] = dst + 1u;
            if ((p.flags & GRID_WRITE_KEYS) != 0u) {
                grid_sort_keys_out[dst] = keys[k];
            }
            if ((p.flags & GRID_VALS_ARE_INDICES) != 0u) {
                grid_sort_vals_out[dst] = i;
            } else {
                grid_sort_vals_out[dst] = grid_sort_vals_in[i];
            }
        }
    }
}
