//! Simplifying a Gauss code until nothing changes: Reidemeister I (a crossing whose two passages are
//! adjacent), Reidemeister II (two crossings adjacent along both strands, one strand over at both),
//! and nugatory crossings (a crossing no other crossing's chord interlaces; R1 is the simplest case).
//!
//! Removing a nugatory crossing is sound: its loop meets the rest of the diagram only at that crossing,
//! so turning the loop over undoes the crossing without touching the others.

use super::gauss_code::GaussCode;

/// Which moves removed crossings, and how many.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Reductions {
    /// Crossings removed by Reidemeister I.
    pub r1: usize,
    /// Crossings removed by Reidemeister II (two per move).
    pub r2: usize,
    /// Nugatory crossings removed that were not plain R1 kinks.
    pub nugatory: usize,
}

/// Reduces the code in place and says what was removed.
pub fn reduce(code: &mut GaussCode) -> Reductions {
    let mut done = Reductions::default();
    loop {
        let len = code.passages.len();
        if len == 0 {
            return done;
        }
        if let Some(i) = find_r1(code) {
            remove_positions(code, &[i, (i + 1) % len]);
            done.r1 += 1;
            continue;
        }
        let other = partner_positions(code);
        if let Some(positions) = find_r2(code, &other) {
            remove_positions(code, &positions);
            done.r2 += 2;
            continue;
        }
        if let Some((i, j)) = find_nugatory(&other) {
            remove_positions(code, &[i, j]);
            done.nugatory += 1;
            continue;
        }
        return done;
    }
}

/// A position whose passage and the next one belong to the same crossing.
fn find_r1(code: &GaussCode) -> Option<usize> {
    let p = &code.passages;
    (0..p.len()).find(|&i| p[i].crossing == p[(i + 1) % p.len()].crossing)
}

/// For each position, the position of the other passage through the same crossing.
fn partner_positions(code: &GaussCode) -> Vec<usize> {
    let mut first = vec![usize::MAX; code.signs.len()];
    let mut other = vec![0; code.passages.len()];
    for (k, p) in code.passages.iter().enumerate() {
        let c = p.crossing as usize;
        if first[c] == usize::MAX {
            first[c] = k;
        } else {
            other[k] = first[c];
            other[first[c]] = k;
        }
    }
    other
}

/// Four positions of two crossings forming an R2 bigon: adjacent along one strand with the same
/// over/under, and their other passages adjacent too.
fn find_r2(code: &GaussCode, other: &[usize]) -> Option<[usize; 4]> {
    let p = &code.passages;
    let len = p.len();
    let adjacent = |a: usize, b: usize| (a + 1) % len == b || (b + 1) % len == a;
    (0..len).find_map(|i| {
        let j = (i + 1) % len;
        let (a, b) = (p[i], p[j]);
        (a.crossing != b.crossing && a.over == b.over && adjacent(other[i], other[j]))
            .then_some([i, j, other[i], other[j]])
    })
}

/// The two positions of a crossing whose chord no other chord crosses: every passage strictly
/// between its two passages has its partner there too.
fn find_nugatory(other: &[usize]) -> Option<(usize, usize)> {
    (0..other.len()).find_map(|i| {
        let j = other[i];
        (i < j && (i + 1..j).all(|k| other[k] > i && other[k] < j)).then_some((i, j))
    })
}

fn remove_positions(code: &mut GaussCode, positions: &[usize]) {
    let mut k = 0;
    code.passages.retain(|_| {
        let keep = !positions.contains(&k);
        k += 1;
        keep
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reduced(text: &str) -> (String, Reductions) {
        let mut code = GaussCode::parse(text).expect("valid code");
        let done = reduce(&mut code);
        let text = code
            .passages
            .iter()
            .map(|p| {
                let sign = if code.signs[p.crossing as usize] > 0 { '+' } else { '-' };
                format!("{}{}{sign}", if p.over { 'O' } else { 'U' }, p.crossing)
            })
            .collect::<Vec<_>>()
            .join(" ");
        (text, done)
    }

    const TREFOIL: &str = "O0+ U1+ O2+ U0+ O1+ U2+";

    /// Reduction takes a kink out by R1 and a bigon by R2 down to the trefoil, leaves the trefoil as it is,
    /// and keeps the figure-eight's clasp whole.
    #[test]
    fn kinks_and_bigons_go_a_trefoil_stays() {
        assert_eq!(reduced(TREFOIL), (TREFOIL.to_owned(), Reductions::default()));
        // A kink (crossing 3) inserted into the trefoil, wrapping around the end of the code.
        let (text, done) = reduced("U3- O0+ U1+ O2+ U0+ O1+ U2+ O3-");
        assert_eq!((text.as_str(), done.r1), (TREFOIL, 1));
        // A bigon: crossings 3 and 4 where one strand passes over another twice.
        let (text, done) = reduced("O0+ O3+ O4- U1+ O2+ U0+ U4- U3+ O1+ U2+");
        assert_eq!((text.as_str(), done.r2), (TREFOIL, 2));
        // Adjacent passages that alternate (over then under) along both strands form a clasp, not a
        // bigon: the figure-eight's code keeps all four crossings.
        let figure_eight = "U0+ O1+ U2- O0+ U3- O2- U1+ O3-";
        assert_eq!(reduced(figure_eight), (figure_eight.to_owned(), Reductions::default()));
    }

    /// A nugatory crossing joining two trefoils is removed though it is not a kink, and a string of kinks
    /// reduces to nothing.
    #[test]
    fn nugatory_crossing_joining_two_knots_goes() {
        // Trefoil (0,1,2), then crossing 9 whose loop holds a second trefoil (3,4,5): chord 9 is
        // interlaced by nothing, so it is nugatory though not a kink.
        let (text, done) = reduced("O0+ U1+ O2+ U0+ O1+ U2+ O9- O3- U4- O5- U3- O4- U5- U9-");
        assert_eq!(done, Reductions { r1: 0, r2: 0, nugatory: 1 });
        assert_eq!(text, "O0+ U1+ O2+ U0+ O1+ U2+ O3- U4- O5- U3- O4- U5-");
        // A string of kinks, all gone.
        assert_eq!(reduced("O0+ U0+ U1- O1- O2+ U3- O3- U2+").0, "");
    }
}
