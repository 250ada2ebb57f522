//! Simplifying a Gauss code until nothing changes: Reidemeister I (a crossing whose two passages are
//! adjacent), Reidemeister II (two crossings adjacent along both strands, one strand over at both),
//! and nugatory crossings (a crossing no other crossing's chord interlaces; R1 is the simplest case).
//!
//! Removing a nugatory crossing is sound: its loop meets the rest of the diagram only at that crossing,
//! so turning the loop over undoes the crossing without touching the others.

use std::collections::BTreeSet;

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

/// Reduces the code in place and says what was removed: Reidemeister I at the first position along
/// the code while there is one, else the first Reidemeister II, else the first nugatory crossing,
/// until none is left. Each move is found in time logarithmic in the code's length (a ring of the
/// passages and ordered sets of the candidate moves, kept as moves open new ones), so a picture of
/// a hundred thousand crossings reduces in well under a second.
pub fn reduce(code: &mut GaussCode) -> Reductions {
    let mut ring = Ring::new(code);
    let mut done = Reductions::default();
    for e in 0..ring.len() {
        ring.consider(e);
    }
    let mut nugatory_stale = true;
    let mut nugatory: BTreeSet<usize> = BTreeSet::new();
    while ring.alive > 0 {
        if let Some(e) = ring.pop_valid(Move::R1) {
            let f = ring.next[e];
            ring.remove(&[e, f]);
            done.r1 += 1;
            continue;
        }
        if let Some(e) = ring.pop_valid(Move::R2) {
            let f = ring.next[e];
            let (pe, pf) = (ring.partner[e], ring.partner[f]);
            ring.remove(&[e, f, pe, pf]);
            done.r2 += 2;
            nugatory_stale = true;
            continue;
        }
        // Removing a kink or a nugatory crossing changes no other chord's interlacing: only a
        // Reidemeister II move can free a chord, so the set is recomputed only after one.
        if nugatory_stale {
            nugatory = ring.nugatory_chords();
            nugatory_stale = false;
        }
        let Some(e) = std::iter::from_fn(|| nugatory.pop_first()).find(|&e| ring.is_alive(e)) else {
            break;
        };
        ring.remove(&[e, ring.partner[e]]);
        done.nugatory += 1;
    }
    let keep = ring.live;
    let mut k = 0;
    code.passages.retain(|_| {
        k += 1;
        keep[k - 1]
    });
    done
}

/// The code's passages as a ring that moves take passages out of, with the candidate moves.
struct Ring<'a> {
    code: &'a GaussCode,
    next: Vec<usize>,
    prev: Vec<usize>,
    live: Vec<bool>,
    alive: usize,
    /// The other passage through the same crossing (`NONE` in a malformed code).
    partner: Vec<usize>,
    /// Passages that may start a kink with the next one, by position along the code.
    r1: BTreeSet<usize>,
    /// Passages that may start a bigon with the next one.
    r2: BTreeSet<usize>,
}

const NONE: usize = usize::MAX;

/// The moves found from the ring's candidate sets.
#[derive(Clone, Copy)]
enum Move {
    R1,
    R2,
}

impl<'a> Ring<'a> {
    fn new(code: &'a GaussCode) -> Self {
        let n = code.passages.len();
        let mut first = vec![NONE; code.signs.len()];
        let mut partner = vec![NONE; n];
        let mut count = vec![0u8; code.signs.len()];
        for (k, p) in code.passages.iter().enumerate() {
            let c = p.crossing as usize;
            count[c] = count[c].saturating_add(1);
            if first[c] == NONE {
                first[c] = k;
            } else {
                partner[k] = first[c];
                partner[first[c]] = k;
            }
        }
        // A crossing met other than twice has no partner.
        for (k, p) in code.passages.iter().enumerate() {
            if count[p.crossing as usize] != 2 {
                partner[k] = NONE;
            }
        }
        Self {
            code,
            next: (0..n).map(|k| (k + 1) % n).collect(),
            prev: (0..n).map(|k| (k + n - 1) % n).collect(),
            live: vec![true; n],
            alive: n,
            partner,
            r1: BTreeSet::new(),
            r2: BTreeSet::new(),
        }
    }

    fn len(&self) -> usize {
        self.live.len()
    }

    fn is_alive(&self, e: usize) -> bool {
        self.live[e]
    }

    /// `e` and the passage after it belong to the same crossing.
    fn is_r1(&self, e: usize) -> bool {
        let f = self.next[e];
        self.live[e] && self.code.passages[e].crossing == self.code.passages[f].crossing
    }

    /// `e` and the passage after it pass two crossings the same way (both over or both under), and
    /// the other strand passes them one after the other too.
    fn is_r2(&self, e: usize) -> bool {
        let f = self.next[e];
        let (a, b) = (self.code.passages[e], self.code.passages[f]);
        let (pe, pf) = (self.partner[e], self.partner[f]);
        self.live[e]
            && a.crossing != b.crossing
            && a.over == b.over
            && pe != NONE
            && pf != NONE
            && (self.next[pe] == pf || self.next[pf] == pe)
    }

    /// Files `e` (with the passage after it) and the pair its partners form among the candidates.
    fn consider(&mut self, e: usize) {
        if !self.live[e] {
            return;
        }
        if self.is_r1(e) {
            self.r1.insert(e);
        }
        if self.is_r2(e) {
            self.r2.insert(e);
        }
    }

    /// The first candidate of a move still valid, taken out of its set.
    fn pop_valid(&mut self, move_: Move) -> Option<usize> {
        loop {
            let e = match move_ {
                Move::R1 => self.r1.pop_first()?,
                Move::R2 => self.r2.pop_first()?,
            };
            let valid = match move_ {
                Move::R1 => self.is_r1(e),
                Move::R2 => self.is_r2(e),
            };
            if valid {
                return Some(e);
            }
        }
    }

    /// Takes the passages out and files the moves their gaps open: the pairs now side by side, and
    /// the pairs of their partners.
    fn remove(&mut self, passages: &[usize]) {
        let mut touched = Vec::with_capacity(2 * passages.len());
        for &e in passages {
            if !self.live[e] {
                continue;
            }
            let (p, n) = (self.prev[e], self.next[e]);
            self.next[p] = n;
            self.prev[n] = p;
            self.live[e] = false;
            self.alive -= 1;
            touched.extend([p, n]);
        }
        for t in touched {
            if !self.live[t] {
                continue;
            }
            for a in [self.prev[t], t] {
                let b = self.next[a];
                self.consider(a);
                let (pa, pb) = (self.partner[a], self.partner[b]);
                if pa != NONE && pb != NONE && self.live[pa] && self.live[pb] {
                    if self.next[pa] == pb {
                        self.consider(pa);
                    }
                    if self.next[pb] == pa {
                        self.consider(pb);
                    }
                }
            }
        }
    }

    /// The first passage of every chord no other chord interlaces: every passage strictly between
    /// its two passages has its partner there too (range minimum and maximum of the partners'
    /// places, by a segment tree over the live passages).
    fn nugatory_chords(&self) -> BTreeSet<usize> {
        let order: Vec<usize> = (0..self.len()).filter(|&e| self.live[e]).collect();
        let mut place = vec![NONE; self.len()];
        for (k, &e) in order.iter().enumerate() {
            place[e] = k;
        }
        let other: Vec<usize> =
            order.iter().map(|&e| self.partner[e]).map(|p| if p == NONE { NONE } else { place[p] }).collect();
        let tree = MinMax::new(&other);
        let mut chords = BTreeSet::new();
        for (i, &j) in other.iter().enumerate() {
            if j == NONE || j <= i {
                continue;
            }
            let (lo, hi) = tree.range(i + 1, j);
            if lo > i && hi < j {
                chords.insert(order[i]);
            }
        }
        chords
    }
}

/// Range minimum and maximum over a fixed array (an iterative segment tree).
struct MinMax {
    size: usize,
    min: Vec<usize>,
    max: Vec<usize>,
}

impl MinMax {
    fn new(values: &[usize]) -> Self {
        let size = values.len().max(1);
        let mut min = vec![NONE; 2 * size];
        let mut max = vec![0; 2 * size];
        for (k, &v) in values.iter().enumerate() {
            // A passage without a partner (`NONE`) interlaces every chord round it.
            min[size + k] = v;
            max[size + k] = v;
        }
        for k in (1..size).rev() {
            min[k] = min[2 * k].min(min[2 * k + 1]);
            max[k] = max[2 * k].max(max[2 * k + 1]);
        }
        Self { size, min, max }
    }

    /// (min, max) over `from..to`; (`NONE`, 0) when empty.
    fn range(&self, from: usize, to: usize) -> (usize, usize) {
        let (mut lo, mut hi) = (NONE, 0);
        let (mut l, mut r) = (from + self.size, to + self.size);
        while l < r {
            if l & 1 == 1 {
                lo = lo.min(self.min[l]);
                hi = hi.max(self.max[l]);
                l += 1;
            }
            if r & 1 == 1 {
                r -= 1;
                lo = lo.min(self.min[r]);
                hi = hi.max(self.max[r]);
            }
            l /= 2;
            r /= 2;
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::super::gauss_code::Passage;
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

    /// The moves one at a time, each found by scanning from the start of the code: the definition
    /// the ring must agree with.
    fn reference_reduce(code: &mut GaussCode) -> Reductions {
        let mut done = Reductions::default();
        loop {
            let p = code.passages.clone();
            let len = p.len();
            if len == 0 {
                return done;
            }
            let mut first = vec![usize::MAX; code.signs.len()];
            let mut other = vec![0; len];
            for (k, q) in p.iter().enumerate() {
                let c = q.crossing as usize;
                if first[c] == usize::MAX {
                    first[c] = k;
                } else {
                    other[k] = first[c];
                    other[first[c]] = k;
                }
            }
            let adjacent = |a: usize, b: usize| (a + 1) % len == b || (b + 1) % len == a;
            let remove: Vec<usize> =
                if let Some(i) = (0..len).find(|&i| p[i].crossing == p[(i + 1) % len].crossing) {
                    done.r1 += 1;
                    vec![i, (i + 1) % len]
                } else if let Some(r) = (0..len).find_map(|i| {
                    let j = (i + 1) % len;
                    (p[i].crossing != p[j].crossing && p[i].over == p[j].over && adjacent(other[i], other[j]))
                        .then_some(vec![i, j, other[i], other[j]])
                }) {
                    done.r2 += 2;
                    r
                } else if let Some((i, j)) = (0..len).find_map(|i| {
                    let j = other[i];
                    (i < j && (i + 1..j).all(|k| other[k] > i && other[k] < j)).then_some((i, j))
                }) {
                    done.nugatory += 1;
                    vec![i, j]
                } else {
                    return done;
                };
            let mut k = 0;
            code.passages.retain(|_| {
                k += 1;
                !remove.contains(&(k - 1))
            });
        }
    }

    /// The ring reduces every code exactly as the moves taken one at a time from the start of the code
    /// do (the same passages left, the same moves counted): random codes of up to 14 crossings, each
    /// crossing passed once over and once under in a random order, many of them reducible.
    #[test]
    fn the_ring_reduces_as_the_moves_one_at_a_time() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let mut moved = 0;
        for _ in 0..20_000 {
            let n = rng.random_range(1..=14usize);
            let mut passages: Vec<Passage> = (0..n as u32)
                .flat_map(|c| {
                    let over = rng.random_bool(0.5);
                    [Passage { crossing: c, over }, Passage { crossing: c, over: !over }]
                })
                .collect();
            // Shuffle, with adjacent repeats made likely so that kinks and bigons occur.
            for k in (1..passages.len()).rev() {
                let j = if rng.random_bool(0.5) { rng.random_range(0..=k) } else { k.saturating_sub(1) };
                passages.swap(k, j);
            }
            let signs = (0..n).map(|_| if rng.random_bool(0.5) { 1 } else { -1 }).collect();
            let code = GaussCode { passages, signs };
            let (mut fast, mut slow) = (code.clone(), code.clone());
            let (a, b) = (reduce(&mut fast), reference_reduce(&mut slow));
            assert_eq!((&fast, a), (&slow, b), "from {code:?}");
            moved += usize::from(a != Reductions::default());
        }
        assert!(moved > 10_000, "only {moved} codes had a move: the test would not see a wrong one");
    }
}
