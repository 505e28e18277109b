// An exclusive prefix sum of u32s in place (draw/scan.rs drives it): each block of BLOCK
// values is scanned in workgroup memory (Hillis & Steele 1986's doubling steps) and its total
// written to `sums`; the sums are scanned the same way, one level up, until one block holds
// them all; then each level adds its block's scanned sum back down.

const BLOCK: u32 = 256u;

struct ScanParams {
    // Values at this level.
    n: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(0) var<uniform> sp: ScanParams;
@group(0) @binding(1) var<storage, read_write> data: array<u32>;
@group(0) @binding(2) var<storage, read_write> sums: array<u32>;

var<workgroup> tmp: array<u32, 256>;

// The workgroup's block, with workgroups folded over y where x runs out.
fn block_of(wid: vec3<u32>, groups: vec3<u32>) -> u32 {
    return wid.x + wid.y * groups.x;
}

@compute @workgroup_size(256)
fn scan_blocks(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(local_invocation_index) l: u32,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let block = block_of(wid, groups);
    let i = block * BLOCK + l;
    var v = 0u;
    if (i < sp.n) {
        v = data[i];
    }
    tmp[l] = v;
    for (var off = 1u; off < BLOCK; off *= 2u) {
        workgroupBarrier();
        var add = 0u;
        if (l >= off) {
            add = tmp[l - off];
        }
        workgroupBarrier();
        tmp[l] += add;
    }
    workgroupBarrier();
    if (i < sp.n) {
        data[i] = tmp[l] - v;
    }
    if (l == BLOCK - 1u && block * BLOCK < sp.n) {
        sums[block] = tmp[l];
    }
}

@compute @workgroup_size(256)
fn add_sums(
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(local_invocation_index) l: u32,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let block = block_of(wid, groups);
    let i = block * BLOCK + l;
    if (i < sp.n) {
        data[i] += sums[block];
    }
}
