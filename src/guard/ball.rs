//! Midpoint–radius ("ball") arithmetic in `f64`: every operation returns an enclosure of
//! the exact result, widened for rounding. Used only by the guard, which can only
//! downgrade a verdict, never make one.

/// An enclosure `[mid − rad, mid + rad]` of a real number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// The midpoint.
    pub mid: f64,
    /// The radius (≥ 0).
    pub rad: f64,
}

/// Why the guard has no value for an expression (never a verdict).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Skip {
    /// Outside what the guard evaluates (an antiderivative, a time symbol at an instant…).
    Unsupported(String),
    /// Outside the domain at this point (a square root of a negative, a division by 0).
    Domain(String),
    /// The work or nesting budget ran out.
    Limit,
}

/// The rounding error of one operation with result `x`.
fn ulps(x: f64, n: f64) -> f64 {
    x.abs() * f64::EPSILON * n + f64::MIN_POSITIVE
}

impl Ball {
    /// A ball of radius 0.
    pub fn exact(x: f64) -> Ball {
        Ball { mid: x, rad: 0.0 }
    }

    /// The nearest `f64` to a value known to lie within one rounding of it.
    pub fn rounded(x: f64) -> Ball {
        Ball {
            mid: x,
            rad: ulps(x, 1.0),
        }
    }

    fn checked(mid: f64, rad: f64) -> Result<Ball, Skip> {
        if mid.is_finite() && rad.is_finite() {
            Ok(Ball { mid, rad })
        } else {
            Err(Skip::Limit)
        }
    }

    /// The lower end.
    pub fn lo(&self) -> f64 {
        self.mid - self.rad
    }

    /// The upper end.
    pub fn hi(&self) -> f64 {
        self.mid + self.rad
    }

    /// `self + o`.
    pub fn plus(self, o: Ball) -> Result<Ball, Skip> {
        let m = self.mid + o.mid;
        Ball::checked(m, self.rad + o.rad + ulps(m, 2.0))
    }

    /// `self − o`.
    pub fn minus(self, o: Ball) -> Result<Ball, Skip> {
        self.plus(o.negate())
    }

    /// `−self`.
    pub fn negate(self) -> Ball {
        Ball {
            mid: -self.mid,
            rad: self.rad,
        }
    }

    /// `self · o`.
    pub fn times(self, o: Ball) -> Result<Ball, Skip> {
        let m = self.mid * o.mid;
        let r = self.mid.abs() * o.rad + o.mid.abs() * self.rad + self.rad * o.rad;
        Ball::checked(m, r * (1.0 + 4.0 * f64::EPSILON) + ulps(m, 2.0))
    }

    /// `1/self`; a ball that may hold 0 has no reciprocal.
    pub fn recip(self) -> Result<Ball, Skip> {
        if self.lo() <= 0.0 && self.hi() >= 0.0 {
            return Err(Skip::Domain("division by a value that may be 0".into()));
        }
        let lo = self.mid.abs() - self.rad;
        let m = 1.0 / self.mid;
        Ball::checked(
            m,
            self.rad / (lo * self.mid.abs()) * 1.000001 + ulps(m, 2.0),
        )
    }

    /// `self / o`.
    pub fn over(self, o: Ball) -> Result<Ball, Skip> {
        self.times(o.recip()?)
    }

    /// `|self|`.
    pub fn abs(self) -> Ball {
        if self.lo() >= 0.0 || self.hi() <= 0.0 {
            return Ball {
                mid: self.mid.abs(),
                rad: self.rad,
            };
        }
        let hi = self.hi().max(-self.lo());
        Ball {
            mid: hi / 2.0,
            rad: hi / 2.0 + ulps(hi, 1.0),
        }
    }

    /// `self^n` for a whole `n` (negative: of the reciprocal).
    pub fn powi(self, n: i64) -> Result<Ball, Skip> {
        if n < 0 {
            return self.recip()?.powi(n.checked_neg().ok_or(Skip::Limit)?);
        }
        if n > 4096 {
            return Err(Skip::Limit);
        }
        let mut out = Ball::exact(1.0);
        let mut base = self;
        let mut k = n;
        while k > 0 {
            if k & 1 == 1 {
                out = out.times(base)?;
            }
            k >>= 1;
            if k > 0 {
                base = base.times(base)?;
            }
        }
        Ok(out)
    }

    /// A monotone function applied to the ends, widened by a few ulps.
    fn monotone(self, f: impl Fn(f64) -> f64) -> Result<Ball, Skip> {
        let (a, b) = (f(self.lo()), f(self.hi()));
        let (lo, hi) = (a.min(b), a.max(b));
        let m = (lo + hi) / 2.0;
        Ball::checked(m, (hi - lo) / 2.0 + ulps(lo.abs().max(hi.abs()), 8.0))
    }

    /// `sqrt(self)`; a ball that dips below 0 only by rounding counts from 0.
    pub fn sqrt(self) -> Result<Ball, Skip> {
        if self.mid < 0.0 && self.hi() < 0.0 {
            return Err(Skip::Domain("the square root of a negative value".into()));
        }
        if self.lo() < 0.0 {
            let hi = self.hi().max(0.0).sqrt();
            return Ball::checked(hi / 2.0, hi / 2.0 + ulps(hi, 4.0));
        }
        self.monotone(f64::sqrt)
    }

    /// The real `q`-th root (odd `q`: negative values too).
    pub fn root(self, q: u32) -> Result<Ball, Skip> {
        if q == 2 {
            return self.sqrt();
        }
        let inv = 1.0 / f64::from(q);
        if q % 2 == 1 {
            return self.monotone(|x| x.signum() * x.abs().powf(inv));
        }
        if self.lo() < 0.0 {
            return Err(Skip::Domain(
                "an even root of a value that may be negative".into(),
            ));
        }
        self.monotone(|x| x.powf(inv))
    }

    /// `exp(self)`.
    pub fn exp(self) -> Result<Ball, Skip> {
        self.monotone(f64::exp)
    }

    /// `ln(self)`, for a ball of positive values.
    pub fn ln(self) -> Result<Ball, Skip> {
        if self.lo() <= 0.0 {
            return Err(Skip::Domain(
                "ln of a value that may not be positive".into(),
            ));
        }
        self.monotone(f64::ln)
    }

    /// `sin(self)` (derivative bounded by 1).
    pub fn sin(self) -> Result<Ball, Skip> {
        let m = self.mid.sin();
        Ball::checked(m, self.rad + ulps(1.0, 8.0))
    }

    /// `cos(self)` (derivative bounded by 1).
    pub fn cos(self) -> Result<Ball, Skip> {
        let m = self.mid.cos();
        Ball::checked(m, self.rad + ulps(1.0, 8.0))
    }

    /// Whether the two balls are apart with a clear margin: an absolute and relative
    /// slack of 10⁻⁹ on top of the radii, so that rounding the guard did not account for
    /// can never make a true step look false.
    pub fn clearly_differs(&self, other: &Ball) -> bool {
        let scale = 1f64.max(self.mid.abs()).max(other.mid.abs());
        (self.mid - other.mid).abs() > 4.0 * (self.rad + other.rad) + 1e-9 * scale
    }
}
