// Virtual obstacles on the GPU: one invocation per subcell. The tip goes to the subcell's centre,
// trocar-constrained IK places the arm (a faithful f32 port of knotlab-hw's closed form:
// kinematics/trocar_ik.rs, arm_ik.rs, limits.rs), forward kinematics poses the moving arm's boxes,
// and oriented-box separating-axis tests check them against the environment and each other.
// Buffer layouts mirror learner/src/obstacles/gpu/buffers.rs.
//
// Precision: sin, cos and atan2 are computed here (Cody-Waite reduction and polynomials, a few ulp),
// not with the built-ins, whose accuracy Vulkan leaves loose (atan: 4096 ulp; sin/cos: 2^-11 absolute).

struct Params {
    origin: vec4<f32>,          // xyz: corner of cell (0, 0); w: subcell size, m
    axis_u: vec4<f32>,          // xyz: first in-plane axis
    axis_v: vec4<f32>,          // xyz: second in-plane axis
    grid: vec4<u32>,            // fine side (n s), subcells per cell side s, cells per side n, subcell count
    counts: vec4<u32>,          // moving boxes, environment boxes, 0, self pairs
    mode: vec4<u32>,            // tool (0 instrument, 1 endoscope), orientation (0 along shaft, 1 jaw direction)
    world_from_base: array<vec4<f32>, 3>,   // rows (r0, r1, r2 | t)
    base_from_world: array<vec4<f32>, 3>,
    dh: array<vec4<f32>, 6>,                // d, theta offset, a, alpha
    geometry: array<vec4<f32>, 3>,          // (d1, a1, a2, a3), (d4, d6, forearm, gamma), (sin gamma, cos gamma, 0, 0)
    limits: array<vec4<f32>, 9>,            // (lower, upper, 0, 0): axes 1-6, roll, pitch, yaw
    tool: array<vec4<f32>, 2>,              // (coupling, shaft, wrist, jaw), (max insertion, min trocar distance, 0, 0)
    trocar: vec4<f32>,
    current: array<vec4<f32>, 3>,           // (q1, q2, q3, q4), (q5, q6, roll, pitch), (yaw, jaw, 0, 0)
    yaw_now: vec4<f32>,                     // the current tip's yaw axis (instruments)
    jaw_dir: vec4<f32>,                     // the asked jaw direction (orientation 1)
}

struct GpuBox {
    rows: array<vec4<f32>, 3>,  // rotation rows | translation: anchor (moving) or world (environment) from box
    half: vec4<f32>,            // half extents, bounding radius
    info: vec4<u32>,            // anchor index, flags (1: tests environment / patient, 2: inserted), 0, 0
}

@group(0) @binding(0) var<storage, read> params: Params;
@group(0) @binding(1) var<storage, read> moving: array<GpuBox>;
@group(0) @binding(2) var<storage, read> environment: array<GpuBox>;
@group(0) @binding(3) var<storage, read> pairs: array<vec4<u32>>;
@group(0) @binding(4) var<storage, read_write> subcells: array<u32>;
@group(0) @binding(5) var<storage, read_write> cells: array<atomic<u32>>;

const PI: f32 = 3.14159265358979323846;
const TAU: f32 = 6.28318530717958647692;
const FRAC_PI_2: f32 = 1.57079632679489661923;
const FRAC_PI_4: f32 = 0.78539816339744830962;
const SINGULAR_EPS: f32 = 1e-10;
const LIMIT_SLACK: f32 = 1e-12;
const STRAIGHT_WRIST_SIN: f32 = 1e-9;
const SAT_EPSILON: f32 = 1e-6;
const MAX_MOVING: u32 = 32u;

const FREE: u32 = 0u;
const COLLIDES: u32 = 1u;
const UNREACHABLE: u32 = 2u;

// ---------------------------------------------------------------- accurate elementary functions

// (sin x, cos x): x minus the nearest multiple of pi/2 in three parts (exact products for the small
// multiples the kinematics meets), then Taylor polynomials on [-pi/4, pi/4].
fn sincos(x: f32) -> vec2<f32> {
    let k = round(x * (2.0 / PI));
    let r = ((x - k * 1.5703125) - k * 4.837512969970703125e-4) - k * 7.54978995489188216e-8;
    let r2 = r * r;
    let s = r + r * r2 * (-1.6666666666666666e-1 + r2 * (8.3333333333333333e-3
        + r2 * (-1.9841269841269841e-4 + r2 * 2.7557319223985891e-6)));
    let c = 1.0 + r2 * (-0.5 + r2 * (4.1666666666666667e-2 + r2 * (-1.3888888888888889e-3
        + r2 * (2.4801587301587302e-5 - r2 * 2.7557319223985891e-7))));
    let q = i32(k) & 3;
    if q == 0 {
        return vec2<f32>(s, c);
    } else if q == 1 {
        return vec2<f32>(c, -s);
    } else if q == 2 {
        return vec2<f32>(-s, -c);
    }
    return vec2<f32>(-c, s);
}

fn negative(x: f32) -> bool {
    return (bitcast<u32>(x) >> 31u) == 1u;
}

// atan2 as Rust's f64::atan2 (signed zeros included): reduction to [0, 1], then to |z| <= tan(pi/8),
// and Cephes' atanf polynomial.
fn atan2_(y: f32, x: f32) -> f32 {
    let ax = abs(x);
    let ay = abs(y);
    let mx = max(ax, ay);
    let mn = min(ax, ay);
    var r = 0.0;
    if mx > 0.0 {
        var a = mn / mx;
        var base = 0.0;
        if a > 0.41421356237309504880 {
            a = (a - 1.0) / (a + 1.0);
            base = FRAC_PI_4;
        }
        let z = a * a;
        r = base + ((((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z
            - 3.33329491539e-1) * z * a + a);
        if ay > ax {
            r = FRAC_PI_2 - r;
        }
    }
    if negative(x) {
        r = PI - r;
    }
    if negative(y) {
        r = -r;
    }
    return r;
}

// ---------------------------------------------------------------- limits (hw kinematics/limits.rs)

fn round_small(x: f32) -> f32 {
    return trunc(x + select(-0.5, 0.5, !negative(x)));
}

fn wrap_angle(q: f32) -> f32 {
    let w = q - TAU * round_small(q / TAU);
    return select(w, w + TAU, w <= -PI);
}

fn limit_contains(l: vec4<f32>, q: f32) -> bool {
    return q >= l.x - LIMIT_SLACK && q <= l.y + LIMIT_SLACK;
}

// (angle, 1) for the equivalent of q inside the limit nearest `near`, or (0, 0).
fn nearest_equivalent(l: vec4<f32>, q: f32, near: f32) -> vec2<f32> {
    let base = q + TAU * round_small((near - q) / TAU);
    if limit_contains(l, base) {
        return vec2<f32>(clamp(base, l.x, l.y), 1.0);
    }
    let up = base + TAU;
    let down = base - TAU;
    let cu = limit_contains(l, up);
    let cd = limit_contains(l, down);
    if cu && cd {
        let pick = select(down, up, abs(up - near) <= abs(down - near));
        return vec2<f32>(clamp(pick, l.x, l.y), 1.0);
    }
    if cu {
        return vec2<f32>(clamp(up, l.x, l.y), 1.0);
    }
    if cd {
        return vec2<f32>(clamp(down, l.x, l.y), 1.0);
    }
    return vec2<f32>(0.0, 0.0);
}

// ---------------------------------------------------------------- rigid transforms

struct Iso {
    r: mat3x3<f32>,
    t: vec3<f32>,
}

fn iso_mul(a: Iso, b: Iso) -> Iso {
    return Iso(a.r * b.r, a.r * b.t + a.t);
}

fn iso_rows(rows: array<vec4<f32>, 3>) -> Iso {
    let r = mat3x3<f32>(
        vec3<f32>(rows[0].x, rows[1].x, rows[2].x),
        vec3<f32>(rows[0].y, rows[1].y, rows[2].y),
        vec3<f32>(rows[0].z, rows[1].z, rows[2].z),
    );
    return Iso(r, vec3<f32>(rows[0].w, rows[1].w, rows[2].w));
}

fn current_arm() -> array<f32, 6> {
    let c = params.current;
    return array<f32, 6>(c[0].x, c[0].y, c[0].z, c[0].w, c[1].x, c[1].y);
}

// ---------------------------------------------------------------- arm branches (hw kinematics/arm_ik.rs)

var<private> branches: array<array<f32, 6>, 8>;
var<private> branch_count: u32;

fn arm_branches(f: Iso, cur: array<f32, 6>) {
    branch_count = 0u;
    let g0 = params.geometry[0];
    let g1 = params.geometry[1];
    let g2 = params.geometry[2];
    let d1 = g0.x;
    let a1 = g0.y;
    let a2 = g0.z;
    let d6 = g1.y;
    let l3 = g1.z;
    let gamma = g1.w;
    let sg = g2.x;
    let cg = g2.y;
    let f0 = f.r[0];
    let f2 = f.r[2];
    let wrist = f.t - d6 * f2;

    let radial = sqrt(wrist.x * wrist.x + wrist.y * wrist.y);
    var azimuth: f32;
    var s1a: f32;
    var c1a: f32;
    if radial < SINGULAR_EPS {
        let sc = sincos(cur[0]);
        azimuth = cur[0];
        s1a = sc.x;
        c1a = sc.y;
    } else {
        azimuth = atan2_(wrist.y, wrist.x);
        s1a = wrist.y / radial;
        c1a = wrist.x / radial;
    }
    for (var shoulder = 0u; shoulder < 2u; shoulder++) {
        var t1 = azimuth;
        var s1 = s1a;
        var c1 = c1a;
        if shoulder == 1u {
            t1 = azimuth + PI;
            s1 = -s1a;
            c1 = -c1a;
        }
        let q1 = nearest_equivalent(params.limits[0], t1, cur[0]);
        if q1.y == 0.0 {
            continue;
        }
        let r = wrist.x * c1 + wrist.y * s1 - a1;
        let s = wrist.z - d1;
        let dist = sqrt(r * r + s * s);
        let cos_elbow = (dist * dist - a2 * a2 - l3 * l3) / (2.0 * a2 * l3);
        if !(cos_elbow >= -1.0 - 1e-12 && cos_elbow <= 1.0 + 1e-12) || dist < SINGULAR_EPS {
            continue;
        }
        let cd = clamp(cos_elbow, -1.0, 1.0);
        let sin_elbow = sqrt(max(1.0 - cd * cd, 0.0));
        let elbow = atan2_(sin_elbow, cd);
        let ch = s / dist;
        let sh = r / dist;
        for (var e = 0u; e < 2u; e++) {
            let sign = select(-1.0, 1.0, e == 0u);
            let delta = sign * elbow;
            let sd = sign * sin_elbow;
            let ky = l3 * sd;
            let kx = a2 + l3 * cd;
            let ck = kx / dist;
            let sk = ky / dist;
            let c_a = ch * ck + sh * sk;
            let s_a = sh * ck - ch * sk;
            let q2_raw = atan2_(s_a, c_a);
            let q3_raw = gamma + delta;
            let q2 = nearest_equivalent(params.limits[1], q2_raw, cur[1]);
            if q2.y == 0.0 {
                continue;
            }
            let q3 = nearest_equivalent(params.limits[2], q3_raw, cur[2]);
            if q3.y == 0.0 {
                continue;
            }
            let c_b = cg * cd - sg * sd;
            let s_b = sg * cd + cg * sd;
            let c_sum = c_a * c_b - s_a * s_b;
            let s_sum = s_a * c_b + c_a * s_b;
            let s23 = -s_sum;
            let c23 = -c_sum;
            let r0 = vec3<f32>(c1 * c23, s1 * c23, -s23);
            let r1 = vec3<f32>(s1, -c1, 0.0);
            let r2 = vec3<f32>(-c1 * s23, -s1 * s23, -c23);
            let m00 = dot(r0, f0);
            let m10 = dot(r1, f0);
            let m20 = dot(r2, f0);
            let m02 = -dot(r0, f2);
            let m12 = -dot(r1, f2);
            let m22 = -dot(r2, f2);
            let sb = sqrt(m02 * m02 + m12 * m12);
            let b = atan2_(sb, m22);
            var a: f32;
            var sa: f32;
            var ca: f32;
            if sb < SINGULAR_EPS {
                let sc = sincos(cur[3]);
                a = cur[3];
                sa = sc.x;
                ca = sc.y;
            } else {
                a = atan2_(m12, m02);
                sa = m12 / sb;
                ca = m02 / sb;
            }
            let n00 = m22 * (ca * m00 + sa * m10) - sb * m20;
            let n10 = -sa * m00 + ca * m10;
            let c = atan2_(n10, n00);
            let n_wrist = select(2u, 1u, sb < SINGULAR_EPS);
            for (var w = 0u; w < n_wrist; w++) {
                var wa = a;
                var wb = b;
                var wc = c;
                if w == 1u {
                    wa = a + PI;
                    wb = -b;
                    wc = c + PI;
                }
                let q5_raw = -wb - PI;
                let q4 = nearest_equivalent(params.limits[3], wa, cur[3]);
                if q4.y == 0.0 {
                    continue;
                }
                let q5 = nearest_equivalent(params.limits[4], q5_raw, cur[4]);
                if q5.y == 0.0 {
                    continue;
                }
                branches[branch_count] = array<f32, 6>(q1.x, q2.x, q3.x, q4.x, q5.x, wrap_angle(-wc));
                branch_count += 1u;
            }
        }
    }
}

fn joint_distance_sq(a: array<f32, 6>, b: array<f32, 6>) -> f32 {
    var sum = 0.0;
    sum += (a[0] - b[0]) * (a[0] - b[0]);
    sum += (a[1] - b[1]) * (a[1] - b[1]);
    sum += (a[2] - b[2]) * (a[2] - b[2]);
    sum += (a[3] - b[3]) * (a[3] - b[3]);
    sum += (a[4] - b[4]) * (a[4] - b[4]);
    sum += (a[5] - b[5]) * (a[5] - b[5]);
    return sum;
}

// ---------------------------------------------------------------- trocar IK (hw kinematics/trocar_ik.rs)

// The solution: arm axes, then roll, pitch, yaw.
var<private> solution: array<f32, 9>;

// (q6, roll, cost, 1) of the split of the shaft rotation nearest the current pair, or w = 0.
fn split_candidate(e: f32, q6_now: f32, roll_now: f32) -> vec4<f32> {
    let l6 = params.limits[5];
    let lr = params.limits[6];
    let t_lo = max(l6.x - q6_now, e - (lr.y - roll_now));
    let t_hi = min(l6.y - q6_now, e - (lr.x - roll_now));
    if t_lo <= t_hi {
        let t = clamp(0.5 * e, t_lo, t_hi);
        return vec4<f32>(q6_now + t, roll_now + (e - t), t * t + (e - t) * (e - t), 1.0);
    }
    return vec4<f32>(0.0);
}

fn split_shaft_rotation(total: f32, q6_now: f32, roll_now: f32) -> vec4<f32> {
    let base = wrap_angle(total - q6_now - roll_now);
    let first = split_candidate(base, q6_now, roll_now);
    if first.w != 0.0 && abs(first.z - 0.5 * base * base) <= 1e-12 {
        return first;
    }
    var best = vec4<f32>(0.0);
    for (var k = -3; k <= 3; k++) {
        let c = split_candidate(base + TAU * f32(k), q6_now, roll_now);
        if c.w != 0.0 && (best.w == 0.0 || c.z < best.z) {
            best = c;
        }
    }
    return best;
}

fn any_perpendicular(v: vec3<f32>) -> vec3<f32> {
    var helper = vec3<f32>(0.0, 1.0, 0.0);
    if abs(v.x) < 0.9 {
        helper = vec3<f32>(1.0, 0.0, 0.0);
    }
    return normalize(cross(v, helper));
}

fn current_yaw_axis(jaw: vec3<f32>) -> vec3<f32> {
    let y_now = params.yaw_now.xyz;
    let perp = y_now - jaw * dot(jaw, y_now);
    let n = length(perp);
    if n > 1e-6 {
        return perp / n;
    }
    return any_perpendicular(jaw);
}

fn solve_instrument(tip: vec3<f32>, jaw: vec3<f32>, yaw_axis: vec3<f32>, either_sign: bool) -> bool {
    let coupling = params.tool[0].x;
    let shaft_m = params.tool[0].y;
    let wrist_m = params.tool[0].z;
    let jaw_m = params.tool[0].w;
    let trocar = params.trocar.xyz;
    let yaw_point = tip - jaw_m * jaw;
    let d = yaw_point - trocar;
    let d_perp = d - yaw_axis * dot(yaw_axis, d);
    let n = length(d_perp);
    if n < 1e-9 {
        return false;
    }
    let wrist = d_perp / n;
    let pitch_point = yaw_point - wrist_m * wrist;
    let e = pitch_point - trocar;
    let depth = length(e);
    if depth < params.tool[1].y || depth > params.tool[1].x {
        return false;
    }
    let shaft = e / depth;
    let x_roll = cross(yaw_axis, wrist);
    let y_roll = cross(shaft, x_roll);
    let pitch = atan2_(-dot(wrist, y_roll), dot(wrist, shaft));
    let yaw = atan2_(dot(jaw, x_roll), dot(jaw, wrist));
    let lp = params.limits[7];
    let ly = params.limits[8];
    let ok0 = limit_contains(lp, pitch) && limit_contains(ly, yaw);
    let ok1 = either_sign && limit_contains(lp, -pitch) && limit_contains(ly, -yaw);
    if !ok0 && !ok1 {
        return false;
    }
    let flange_t = pitch_point - (coupling + shaft_m) * shaft;
    let world_from_flange = Iso(mat3x3<f32>(x_roll, y_roll, shaft), flange_t);
    let base_from_flange = iso_mul(iso_rows(params.base_from_world), world_from_flange);
    let cur = current_arm();
    arm_branches(base_from_flange, cur);
    let roll_now = params.current[1].z;
    let pitch_now = params.current[1].w;
    let yaw_now = params.current[2].x;
    var found = false;
    var best_cost = 0.0;
    for (var b = 0u; b < branch_count; b++) {
        let branch = branches[b];
        var arm = branch;
        arm[5] = cur[5];
        let arm_cost = joint_distance_sq(arm, cur);
        for (var w = 0u; w < 2u; w++) {
            if (w == 0u && !ok0) || (w == 1u && !ok1) {
                continue;
            }
            let p = select(-pitch, pitch, w == 0u);
            let y = select(-yaw, yaw, w == 0u);
            let turn = select(PI, 0.0, w == 0u);
            let split = split_shaft_rotation(branch[5] + turn, cur[5], roll_now);
            if split.w == 0.0 {
                continue;
            }
            let cost = arm_cost + split.z + (p - pitch_now) * (p - pitch_now) + (y - yaw_now) * (y - yaw_now);
            if !found || cost < best_cost {
                found = true;
                best_cost = cost;
                solution = array<f32, 9>(arm[0], arm[1], arm[2], arm[3], arm[4], split.x, split.y, p, y);
            }
        }
    }
    return found;
}

fn solve_endoscope(tip: vec3<f32>) -> bool {
    let trocar = params.trocar.xyz;
    let e = tip - trocar;
    let depth = length(e);
    if depth > params.tool[1].x {
        return false;
    }
    let shaft = e / depth;
    let x = any_perpendicular(shaft);
    let flange_t = tip - (params.tool[0].x + params.tool[0].y) * shaft;
    let world_from_flange = Iso(mat3x3<f32>(x, cross(shaft, x), shaft), flange_t);
    let base_from_flange = iso_mul(iso_rows(params.base_from_world), world_from_flange);
    let cur = current_arm();
    arm_branches(base_from_flange, cur);
    let q6 = clamp(cur[5], params.limits[5].x, params.limits[5].y);
    var found = false;
    var best_cost = 0.0;
    for (var b = 0u; b < branch_count; b++) {
        var arm = branches[b];
        arm[5] = q6;
        let cost = joint_distance_sq(arm, cur);
        if !found || cost < best_cost {
            found = true;
            best_cost = cost;
            solution = array<f32, 9>(arm[0], arm[1], arm[2], arm[3], arm[4], arm[5], 0.0, 0.0, 0.0);
        }
    }
    return found;
}

fn solve_tip(tip: vec3<f32>) -> bool {
    let trocar = params.trocar.xyz;
    let to_tip = tip - trocar;
    let distance = length(to_tip);
    if distance < params.tool[1].y {
        return false;
    }
    if params.mode.x == 1u {
        return solve_endoscope(tip);
    }
    if params.mode.y == 0u {
        let jaw = to_tip / distance;
        return solve_instrument(tip, jaw, current_yaw_axis(jaw), false);
    }
    let jaw = params.jaw_dir.xyz / length(params.jaw_dir.xyz);
    let normal = cross(jaw, to_tip);
    let n = length(normal);
    if n <= STRAIGHT_WRIST_SIN * distance {
        return solve_instrument(tip, jaw, current_yaw_axis(jaw), false);
    }
    return solve_instrument(tip, jaw, normal / n, true);
}

// ---------------------------------------------------------------- forward kinematics (anchors)

var<private> anchors: array<Iso, 10>;

fn dh_transform(row: vec4<f32>, q: f32) -> Iso {
    let st_ct = sincos(q + row.y);
    let sa_ca = sincos(row.w);
    let st = st_ct.x;
    let ct = st_ct.y;
    let sa = sa_ca.x;
    let ca = sa_ca.y;
    // Columns of [[ct, -st ca, st sa], [st, ct ca, -ct sa], [0, sa, ca]].
    let r = mat3x3<f32>(vec3<f32>(ct, st, 0.0), vec3<f32>(-st * ca, ct * ca, sa), vec3<f32>(st * sa, -ct * sa, ca));
    return Iso(r, vec3<f32>(row.z * ct, row.z * st, row.x));
}

fn turn_after(z: f32, axis: u32, q: f32) -> Iso {
    let sc = sincos(q);
    let s = sc.x;
    let c = sc.y;
    var r: mat3x3<f32>;
    if axis == 0u {
        r = mat3x3<f32>(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, c, s), vec3<f32>(0.0, -s, c));
    } else if axis == 1u {
        r = mat3x3<f32>(vec3<f32>(c, 0.0, -s), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(s, 0.0, c));
    } else {
        r = mat3x3<f32>(vec3<f32>(c, s, 0.0), vec3<f32>(-s, c, 0.0), vec3<f32>(0.0, 0.0, 1.0));
    }
    return Iso(r, vec3<f32>(0.0, 0.0, z));
}

fn pose_anchors() {
    let world_from_base = iso_rows(params.world_from_base);
    anchors[0] = world_from_base;
    var base_from_frame = Iso(mat3x3<f32>(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0)), vec3<f32>(0.0));
    for (var i = 0u; i < 6u; i++) {
        base_from_frame = iso_mul(base_from_frame, dh_transform(params.dh[i], solution[i]));
        anchors[i + 1u] = iso_mul(world_from_base, base_from_frame);
    }
    let flange = anchors[6];
    if params.mode.x == 0u {
        anchors[7] = iso_mul(flange, turn_after(params.tool[0].x, 2u, solution[6]));
        anchors[8] = iso_mul(anchors[7], turn_after(params.tool[0].y, 0u, solution[7]));
        anchors[9] = iso_mul(anchors[8], turn_after(params.tool[0].z, 1u, solution[8]));
    } else {
        anchors[7] = flange;
        anchors[8] = flange;
        anchors[9] = flange;
    }
}

// ---------------------------------------------------------------- oriented boxes

struct Obb {
    c: vec3<f32>,
    r: mat3x3<f32>,
    h: vec3<f32>,
}

var<private> posed: array<Obb, MAX_MOVING>;

// The separating-axis test of learner/src/obstacles/obb.rs, unrolled: r_ij = A_i . B_j, t the centre
// offset in A's frame, |r_ij| + SAT_EPSILON for the radii; boxes touching count as overlapping.
fn obb_intersects(a: Obb, b: Obb) -> bool {
    let a0 = a.r[0];
    let a1 = a.r[1];
    let a2 = a.r[2];
    let b0 = b.r[0];
    let b1 = b.r[1];
    let b2 = b.r[2];
    // Rows of r (fixed i) and their absolute values.
    let r0 = vec3<f32>(dot(a0, b0), dot(a0, b1), dot(a0, b2));
    let r1 = vec3<f32>(dot(a1, b0), dot(a1, b1), dot(a1, b2));
    let r2 = vec3<f32>(dot(a2, b0), dot(a2, b1), dot(a2, b2));
    let e = vec3<f32>(SAT_EPSILON);
    let q0 = abs(r0) + e;
    let q1 = abs(r1) + e;
    let q2 = abs(r2) + e;
    let d = b.c - a.c;
    let t = vec3<f32>(dot(d, a0), dot(d, a1), dot(d, a2));
    let ha = a.h;
    let hb = b.h;
    // A's faces.
    if abs(t.x) > ha.x + dot(hb, q0) || abs(t.y) > ha.y + dot(hb, q1) || abs(t.z) > ha.z + dot(hb, q2) {
        return false;
    }
    // B's faces: column j of r.
    let c0 = vec3<f32>(q0.x, q1.x, q2.x);
    let c1 = vec3<f32>(q0.y, q1.y, q2.y);
    let c2 = vec3<f32>(q0.z, q1.z, q2.z);
    if abs(t.x * r0.x + t.y * r1.x + t.z * r2.x) > dot(ha, c0) + hb.x
        || abs(t.x * r0.y + t.y * r1.y + t.z * r2.y) > dot(ha, c1) + hb.y
        || abs(t.x * r0.z + t.y * r1.z + t.z * r2.z) > dot(ha, c2) + hb.z {
        return false;
    }
    // A_i x B_j: ra = a[i1] q[i2][j] + a[i2] q[i1][j], rb = b[j1] q[i][j2] + b[j2] q[i][j1],
    // proj = t[i2] r[i1][j] - t[i1] r[i2][j], with i1 = i + 1, i2 = i + 2 (mod 3), likewise j.
    // i = 0
    if abs(t.z * r1.x - t.y * r2.x) > ha.y * q2.x + ha.z * q1.x + hb.y * q0.z + hb.z * q0.y
        || abs(t.z * r1.y - t.y * r2.y) > ha.y * q2.y + ha.z * q1.y + hb.z * q0.x + hb.x * q0.z
        || abs(t.z * r1.z - t.y * r2.z) > ha.y * q2.z + ha.z * q1.z + hb.x * q0.y + hb.y * q0.x {
        return false;
    }
    // i = 1
    if abs(t.x * r2.x - t.z * r0.x) > ha.z * q0.x + ha.x * q2.x + hb.y * q1.z + hb.z * q1.y
        || abs(t.x * r2.y - t.z * r0.y) > ha.z * q0.y + ha.x * q2.y + hb.z * q1.x + hb.x * q1.z
        || abs(t.x * r2.z - t.z * r0.z) > ha.z * q0.z + ha.x * q2.z + hb.x * q1.y + hb.y * q1.x {
        return false;
    }
    // i = 2
    if abs(t.y * r0.x - t.x * r1.x) > ha.x * q1.x + ha.y * q0.x + hb.y * q2.z + hb.z * q2.y
        || abs(t.y * r0.y - t.x * r1.y) > ha.x * q1.y + ha.y * q0.y + hb.z * q2.x + hb.x * q2.z
        || abs(t.y * r0.z - t.x * r1.z) > ha.x * q1.z + ha.y * q0.z + hb.x * q2.y + hb.y * q2.x {
        return false;
    }
    return true;
}

fn spheres_meet(a: vec3<f32>, ra: f32, b: vec3<f32>, rb: f32) -> bool {
    let d = a - b;
    return dot(d, d) <= (ra + rb) * (ra + rb);
}

// ---------------------------------------------------------------- the tile's broad phase
//
// A workgroup's 64 subcells form a short strip of the grid. Each invocation poses its arm, the
// workgroup bounds where each moving box's centre goes over the strip, and together they list the
// environment boxes each moving box can reach at all (sphere against the swept box, as the CPU
// backend does per cell); only those are then tested. The pruning is conservative: it changes no
// verdict, only the work.

const ENV_WORDS: u32 = 8u;          // candidate bits per moving box: up to 256 environment boxes
var<workgroup> sweep_lo: array<array<atomic<u32>, 3>, MAX_MOVING>;
var<workgroup> sweep_hi: array<array<atomic<u32>, 3>, MAX_MOVING>;
var<workgroup> candidates: array<array<atomic<u32>, ENV_WORDS>, MAX_MOVING>;
var<workgroup> reachable: atomic<u32>;

// f32 bits mapped so that unsigned order is numeric order.
fn ordered(x: f32) -> u32 {
    let b = bitcast<u32>(x);
    return select(b ^ 0x80000000u, ~b, negative(x));
}

fn unordered(u: u32) -> f32 {
    return bitcast<f32>(select(~u, u ^ 0x80000000u, (u & 0x80000000u) != 0u));
}

fn pose_moving() {
    let n_moving = min(params.counts.x, MAX_MOVING);
    for (var m = 0u; m < n_moving; m++) {
        let mb = moving[m];
        let world = iso_mul(anchors[mb.info.x], iso_rows(mb.rows));
        posed[m] = Obb(world.t, world.r, mb.half.xyz);
        for (var a = 0u; a < 3u; a++) {
            atomicMin(&sweep_lo[m][a], ordered(world.t[a]));
            atomicMax(&sweep_hi[m][a], ordered(world.t[a]));
        }
    }
}

// Candidate bits for the pairs (moving box, environment box) this invocation is dealt.
fn list_candidates(local: u32) {
    let n_moving = min(params.counts.x, MAX_MOVING);
    let n_env = min(params.counts.y, 32u * ENV_WORDS);
    for (var p = local; p < n_moving * n_env; p += 64u) {
        let m = p / n_env;
        let e = p % n_env;
        let mb = moving[m];
        let eb = environment[e];
        if (mb.info.y & 1u) == 0u || ((mb.info.y & 2u) != 0u && (eb.info.y & 1u) != 0u) {
            continue;
        }
        let lo_x = atomicLoad(&sweep_lo[m][0]);
        let hi_x = atomicLoad(&sweep_hi[m][0]);
        if lo_x > hi_x {
            continue;       // no subcell of the strip reached
        }
        let lo = vec3<f32>(unordered(lo_x), unordered(atomicLoad(&sweep_lo[m][1])), unordered(atomicLoad(&sweep_lo[m][2])));
        let hi = vec3<f32>(unordered(hi_x), unordered(atomicLoad(&sweep_hi[m][1])), unordered(atomicLoad(&sweep_hi[m][2])));
        let c = vec3<f32>(eb.rows[0].w, eb.rows[1].w, eb.rows[2].w);
        let gap = max(max(lo - c, c - hi), vec3<f32>(0.0));
        let reach = mb.half.w + eb.half.w;
        if dot(gap, gap) <= reach * reach {
            atomicOr(&candidates[m][e / 32u], 1u << (e % 32u));
        }
    }
}

fn collides() -> bool {
    let n_moving = min(params.counts.x, MAX_MOVING);
    for (var m = 0u; m < n_moving; m++) {
        let radius = moving[m].half.w;
        let p = posed[m];
        for (var w = 0u; w < ENV_WORDS; w++) {
            var bits = atomicLoad(&candidates[m][w]);
            while bits != 0u {
                let e = w * 32u + firstTrailingBit(bits);
                bits &= bits - 1u;
                let eb = environment[e];
                let ew = iso_rows(eb.rows);
                if spheres_meet(p.c, radius, ew.t, eb.half.w) && obb_intersects(p, Obb(ew.t, ew.r, eb.half.xyz)) {
                    return true;
                }
            }
        }
    }
    for (var k = 0u; k < params.counts.w; k++) {
        let pair = pairs[k];
        let a = posed[pair.x];
        let b = posed[pair.y];
        if spheres_meet(a.c, moving[pair.x].half.w, b.c, moving[pair.y].half.w) && obb_intersects(a, b) {
            return true;
        }
    }
    return false;
}

// ---------------------------------------------------------------- entry point

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    for (var m = local; m < MAX_MOVING; m += 64u) {
        for (var a = 0u; a < 3u; a++) {
            atomicStore(&sweep_lo[m][a], 0xffffffffu);
            atomicStore(&sweep_hi[m][a], 0u);
        }
        for (var w = 0u; w < ENV_WORDS; w++) {
            atomicStore(&candidates[m][w], 0u);
        }
    }
    workgroupBarrier();
    let k = id.x;
    let side = params.grid.x;
    let x = k % side;
    let y = k / side;
    var verdict = UNREACHABLE;
    if k < params.grid.w {
        let h = params.origin.w;
        let tip = params.origin.xyz + params.axis_u.xyz * ((f32(x) + 0.5) * h) + params.axis_v.xyz * ((f32(y) + 0.5) * h);
        if solve_tip(tip) {
            atomicAdd(&reachable, 1u);
            pose_anchors();
            pose_moving();
            verdict = FREE;
        }
    }
    workgroupBarrier();
    list_candidates(local);
    workgroupBarrier();
    if k < params.grid.w {
        if verdict == FREE && collides() {
            verdict = COLLIDES;
        }
        subcells[k] = verdict;
        if verdict != FREE {
            let s = params.grid.y;
            let cell = (y / s) * params.grid.z + x / s;
            atomicOr(&cells[cell], 1u << (verdict - 1u));
        }
    }
    if local == 0u {
        atomicAdd(&cells[params.grid.z * params.grid.z], atomicLoad(&reachable));
    }
}
