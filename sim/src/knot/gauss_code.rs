//! The signed Gauss code: the crossings' passages in order along the closed curve, each crossing met
//! once over and once under, each with its sign.

use super::crossings::Crossing;

/// One passage through a crossing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Passage {
    /// Which crossing (an index into [`GaussCode::signs`]).
    pub crossing: u32,
    /// Whether the curve passes over here.
    pub over: bool,
}

/// A cyclic signed Gauss code.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct GaussCode {
    /// Passages in order along the curve (cyclic: the last is followed by the first).
    pub passages: Vec<Passage>,
    /// Sign of each crossing, by crossing index (+1 right-handed, -1 left-handed).
    pub signs: Vec<i8>,
}

impl GaussCode {
    /// The code of a picture's crossings, passages sorted by position along the curve.
    pub fn from_crossings(crossings: &[Crossing]) -> Self {
        let mut at: Vec<(f64, Passage)> = Vec::with_capacity(2 * crossings.len());
        for (k, c) in crossings.iter().enumerate() {
            let crossing = k as u32;
            at.push((c.over_at, Passage { crossing, over: true }));
            at.push((c.under_at, Passage { crossing, over: false }));
        }
        at.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        Self {
            passages: at.into_iter().map(|(_, p)| p).collect(),
            signs: crossings.iter().map(|c| c.sign).collect(),
        }
    }

    /// A code from a compact text, for tests and debugging: passages separated by spaces, each
    /// `O` or `U`, the crossing number, and its sign (`O1+ U2+ O3- ...`); signs must agree.
    pub fn parse(text: &str) -> Option<Self> {
        let mut passages = Vec::new();
        let mut signs: Vec<Option<i8>> = Vec::new();
        for token in text.split_whitespace() {
            let over = match token.as_bytes().first()? {
                b'O' => true,
                b'U' => false,
                _ => return None,
            };
            let sign = match token.as_bytes().last()? {
                b'+' => 1,
                b'-' => -1,
                _ => return None,
            };
            let crossing: usize = token.get(1..token.len() - 1)?.parse().ok()?;
            if signs.len() <= crossing {
                signs.resize(crossing + 1, None);
            }
            if signs[crossing].is_some_and(|s| s != sign) {
                return None;
            }
            signs[crossing] = Some(sign);
            passages.push(Passage { crossing: crossing as u32, over });
        }
        Some(Self { passages, signs: signs.into_iter().map(|s| s.unwrap_or(0)).collect() })
    }

    /// Number of crossings still in the code.
    pub fn crossings(&self) -> usize {
        self.passages.len() / 2
    }

    /// Sum of the signs of the crossings still in the code.
    pub fn writhe(&self) -> i32 {
        self.passages.iter().filter(|p| p.over).map(|p| i32::from(self.signs[p.crossing as usize])).sum()
    }

    /// Crossing indices still in the code, in order of their first passage.
    pub fn crossing_ids(&self) -> Vec<u32> {
        let mut seen = vec![false; self.signs.len()];
        let mut ids = Vec::with_capacity(self.crossings());
        for p in &self.passages {
            if !seen[p.crossing as usize] {
                seen[p.crossing as usize] = true;
                ids.push(p.crossing);
            }
        }
        ids
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Crossings become passages in order along the curve with their signs and writhe, and a code whose
    /// crossing changes sign between its passages is refused.
    #[test]
    fn passages_follow_the_curve() {
        let crossings = [
            Crossing { over_at: 5.5, under_at: 1.25, sign: 1 },
            Crossing { over_at: 2.0, under_at: 7.0, sign: -1 },
        ];
        let code = GaussCode::from_crossings(&crossings);
        assert_eq!(code, GaussCode::parse("U0+ O1- O0+ U1-").expect("valid code"));
        assert_eq!(code.writhe(), 0);
        assert_eq!(code.crossing_ids(), vec![0, 1]);
        assert!(GaussCode::parse("O0+ U0-").is_none());
    }
}
