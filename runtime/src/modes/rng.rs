//! A small deterministic random source (SplitMix64) for seeds, loops and γ: no_std, and the
//! same numbers for the same seed on every platform.

use super::complex::Complex;

#[derive(Clone, Debug)]
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Rng(seed ^ 0x5DEE_CE66_D1CE_4E5B)
    }

    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1).
    pub(crate) fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64)
    }

    /// A standard complex normal number (Box–Muller).
    pub(crate) fn complex_normal(&mut self) -> Complex {
        let r = crate::math::sqrt(-libm::log(self.uniform()));
        let t = 2.0 * core::f64::consts::PI * self.uniform();
        Complex::new(r * libm::cos(t), r * libm::sin(t))
    }
}
