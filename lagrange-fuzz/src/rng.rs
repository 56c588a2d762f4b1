//! SplitMix64: a tiny, well-mixed generator, so that an input is a pure
//! function of `(seed, index)` on every platform and every version of every
//! dependency (an external crate's stream may change between releases).

/// One input's random stream.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// The stream of input `index` under `seed`: independent of how inputs
    /// are spread over workers, so any input can be regenerated alone.
    pub fn for_input(seed: u64, index: u64) -> Self {
        let mut r = Rng(seed ^ 0x6c61_6772_616e_6765); // "lagrange"
        let s = r.next_u64();
        Rng(s ^ index.wrapping_mul(0x9e37_79b9_7f4a_7c15))
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (`n > 0`); the modulo bias is irrelevant here.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// Uniform in `lo..=hi`.
    pub fn range(&mut self, lo: usize, hi: usize) -> usize {
        lo + self.below(hi - lo + 1)
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64 <= p
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }

    /// An index into `weights`, drawn in proportion to them.
    pub fn weighted(&mut self, weights: &[u32]) -> usize {
        let total: u64 = weights.iter().map(|&w| w as u64).sum();
        let mut x = self.next_u64() % total;
        for (i, &w) in weights.iter().enumerate() {
            if x < w as u64 {
                return i;
            }
            x -= w as u64;
        }
        unreachable!("x < total")
    }

    /// Log-uniform in `1..=max`: as many sizes near 10 as near 10 000, so
    /// that most inputs stay small while every decade is visited.
    pub fn log_size(&mut self, max: usize) -> usize {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        ((max as f64).powf(u).floor() as usize).clamp(1, max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_input_stream_depends_only_on_seed_and_index() {
        let a: Vec<u64> = (0..4).map(|_| Rng::for_input(7, 3).next_u64()).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]));
        assert_ne!(
            Rng::for_input(7, 3).next_u64(),
            Rng::for_input(7, 4).next_u64()
        );
        assert_ne!(
            Rng::for_input(7, 3).next_u64(),
            Rng::for_input(8, 3).next_u64()
        );
    }

    #[test]
    fn log_sizes_visit_every_decade_and_stay_in_bounds() {
        let mut r = Rng::for_input(1, 1);
        let sizes: Vec<usize> = (0..4000).map(|_| r.log_size(10_000)).collect();
        assert!(sizes.iter().all(|&n| (1..=10_000).contains(&n)));
        for decade in [1, 10, 100, 1000] {
            let n = sizes
                .iter()
                .filter(|&&s| s >= decade && s < decade * 10)
                .count();
            // A quarter of 4000 expected per decade; 700 is far below any
            // plausible fluctuation (standard deviation about 27).
            assert!(n > 700, "decade {decade}: {n}");
        }
    }
}
