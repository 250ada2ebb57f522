//! Invariants of a Gauss code: the determinant |Delta(-1)| from the crossing/arc (colouring) matrix,
//! computed exactly by integer Bareiss elimination, and the writhe.

use super::gauss_code::GaussCode;

/// Most crossings a reduced code may keep for its determinant to be computed: the elimination is
/// cubic in them and its matrix square, and past a hundred or so crossings its integers overflow
/// 128 bits anyway. A knot the rules name has at most 8.
pub const MAX_DETERMINANT_CROSSINGS: usize = 300;

/// The knot determinant |Delta(-1)| of a (closed, one-component) Gauss code; `None` if the code
/// keeps more than [`MAX_DETERMINANT_CROSSINGS`] crossings, the elimination would overflow 128-bit
/// integers (far beyond any thread we classify) or the code is malformed. The empty code (no
/// crossings) has determinant 1.
///
/// Rows are crossings, columns arcs (an arc runs from one under-passage to the next): the over arc
/// gets 2, the incoming and outgoing under arcs -1 each; one row and one column are deleted.
pub fn determinant(code: &GaussCode) -> Option<u64> {
    let n = code.crossings();
    if n <= 1 {
        return Some(1);
    }
    if n > MAX_DETERMINANT_CROSSINGS {
        return None;
    }
    // Dense crossing numbers, and the arc each passage lies on.
    let mut dense = vec![usize::MAX; code.signs.len()];
    for (k, id) in code.crossing_ids().into_iter().enumerate() {
        dense[id as usize] = k;
    }
    // Each crossing is passed exactly once over and once under.
    let mut seen = vec![[0u8; 2]; n];
    for p in &code.passages {
        let row = *dense.get(p.crossing as usize)?;
        seen.get_mut(row)?[usize::from(p.over)] += 1;
    }
    if seen.iter().any(|s| *s != [1, 1]) {
        return None;
    }
    // Arc j starts just after the j-th under-passage; passages before the first under-passage lie on
    // the last arc, which wraps around the end of the code.
    let mut matrix = vec![0i128; n * n];
    let mut arc = n - 1;
    for p in &code.passages {
        let row = dense[p.crossing as usize];
        if p.over {
            matrix[row * n + arc] += 2;
        } else {
            let incoming = arc;
            arc = (arc + 1) % n;
            matrix[row * n + incoming] -= 1;
            matrix[row * n + arc] -= 1;
        }
    }
    // Delete the last row and column.
    let m = n - 1;
    let minor: Vec<i128> = (0..m).flat_map(|r| matrix[r * n..r * n + m].iter().copied()).collect();
    bareiss_abs_det(minor, m).and_then(|d| u64::try_from(d).ok())
}

/// |det| of an `n x n` integer matrix (row-major) by fraction-free Bareiss elimination: every division
/// is exact, so the result is exact; `None` on overflow.
pub fn bareiss_abs_det(mut a: Vec<i128>, n: usize) -> Option<u128> {
    if n == 0 {
        return Some(1);
    }
    let mut previous_pivot: i128 = 1;
    for k in 0..n - 1 {
        if a[k * n + k] == 0 {
            let Some(swap) = (k + 1..n).find(|&r| a[r * n + k] != 0) else {
                return Some(0);
            };
            for c in 0..n {
                a.swap(k * n + c, swap * n + c);
            }
        }
        let pivot = a[k * n + k];
        for i in k + 1..n {
            let lead = a[i * n + k];
            for j in k + 1..n {
                let value = a[i * n + j].checked_mul(pivot)?.checked_sub(lead.checked_mul(a[k * n + j])?)?;
                a[i * n + j] = value / previous_pivot;
            }
            a[i * n + k] = 0;
        }
        previous_pivot = pivot;
    }
    Some(a[n * n - 1].unsigned_abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn det(text: &str) -> Option<u64> {
        determinant(&GaussCode::parse(text).expect("valid code"))
    }

    /// Bareiss elimination gives exact integer determinants, swapping rows past a zero pivot and giving zero
    /// for singular matrices.
    #[test]
    fn bareiss_is_exact() {
        assert_eq!(bareiss_abs_det(vec![2, -1, 0, -1, 2, -1, 0, -1, 2], 3), Some(4));
        // Zero leading pivot needs a row swap.
        assert_eq!(bareiss_abs_det(vec![0, 3, 2, 5], 2), Some(6));
        assert_eq!(bareiss_abs_det(vec![1, 2, 2, 4], 2), Some(0));
        // A singular column: no pivot below.
        assert_eq!(bareiss_abs_det(vec![0, 1, 0, 1], 2), Some(0));
    }

    /// The unknot, trefoil, figure-eight, cinquefoil and granny codes give their known determinants, and a
    /// code with a crossing missing its over passage gives none.
    #[test]
    fn determinants_of_known_knots() {
        assert_eq!(det(""), Some(1));
        assert_eq!(det("O0+ U1+ O2+ U0+ O1+ U2+"), Some(3));
        assert_eq!(det("U0+ O1+ U2- O0+ U3- O2- U1+ O3-"), Some(5));
        // Cinquefoil: the (2,5) torus knot.
        assert_eq!(det("O0+ U1+ O2+ U3+ O4+ U0+ O1+ U2+ O3+ U4+"), Some(5));
        // Trefoil # trefoil (granny): 3 x 3.
        assert_eq!(det("O0+ U1+ O2+ U0+ O1+ U2+ O3+ U4+ O5+ U3+ O4+ U5+"), Some(9));
        // An ascending unknot diagram: the trefoil's shadow with one crossing changed.
        assert_eq!(det("O0+ O1- O2+ U0+ U1- U2+"), Some(1));
        assert_eq!(det("O0+ U1- U2+ O0+ O1- U2+"), None, "malformed: crossing 2 has no over passage");
    }
}
