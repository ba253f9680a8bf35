//! Angle expressions: `=P1-2`, `=(C1+C2)/2`, `=0.5*P1+20`.

/// The value of the expression `text` (with or without its leading `=`): numbers, tier names
/// (a letter or `_` then letters, digits, `_`), `+ - * /` and parentheses; a name's value is
/// `angle(name)` (a tier's tilt, `None` when there is no such tier cut before).
///
/// ```
/// use facetlab::design::recipe::eval_angle;
/// let tilt = |n: &str| (n == "P1").then_some(41.0);
/// assert_eq!(eval_angle("=P1-2", &tilt).unwrap(), 39.0);
/// assert_eq!(eval_angle("=(P1+43)/2", &tilt).unwrap(), 42.0);
/// assert!(eval_angle("=P2+1", &tilt).unwrap_err().contains("P2"));
/// ```
pub fn eval_angle(text: &str, angle: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
    let t = text.trim();
    let t = t.strip_prefix('=').unwrap_or(t);
    let mut p = Parser {
        s: t.as_bytes(),
        i: 0,
        angle,
    };
    let v = p.sum()?;
    p.space();
    if p.i != p.s.len() {
        return Err(format!(
            "`{text}`: unexpected `{}`",
            String::from_utf8_lossy(&p.s[p.i..])
        ));
    }
    if !v.is_finite() {
        return Err(format!("`{text}` is not a finite number"));
    }
    Ok(v)
}

/// The tier names an expression uses, in order.
pub(crate) fn names(text: &str) -> Vec<String> {
    let t = text.trim().trim_start_matches('=');
    let mut out = Vec::new();
    let b = t.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i].is_ascii_alphabetic() || b[i] == b'_' {
            let j = (i..b.len())
                .find(|&j| !(b[j].is_ascii_alphanumeric() || b[j] == b'_'))
                .unwrap_or(b.len());
            out.push(t[i..j].to_string());
            i = j;
        } else if b[i].is_ascii_digit() || b[i] == b'.' {
            // A number (with an exponent: 1e3) is not a name.
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'.') {
                i += 1;
            }
        } else {
            i += 1;
        }
    }
    out
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
    angle: &'a dyn Fn(&str) -> Option<f64>,
}

impl Parser<'_> {
    fn space(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.space();
        self.s.get(self.i).copied()
    }

    fn sum(&mut self) -> Result<f64, String> {
        let mut v = self.product()?;
        while let Some(c @ (b'+' | b'-')) = self.peek() {
            self.i += 1;
            let w = self.product()?;
            v = if c == b'+' { v + w } else { v - w };
        }
        Ok(v)
    }

    fn product(&mut self) -> Result<f64, String> {
        let mut v = self.unary()?;
        while let Some(c @ (b'*' | b'/')) = self.peek() {
            self.i += 1;
            let w = self.unary()?;
            v = if c == b'*' { v * w } else { v / w };
        }
        Ok(v)
    }

    fn unary(&mut self) -> Result<f64, String> {
        match self.peek() {
            Some(b'-') => {
                self.i += 1;
                Ok(-self.unary()?)
            }
            Some(b'+') => {
                self.i += 1;
                self.unary()
            }
            _ => self.atom(),
        }
    }

    fn atom(&mut self) -> Result<f64, String> {
        match self.peek() {
            Some(b'(') => {
                self.i += 1;
                let v = self.sum()?;
                if self.peek() != Some(b')') {
                    return Err("a `(` is not closed".into());
                }
                self.i += 1;
                Ok(v)
            }
            Some(c) if c.is_ascii_digit() || c == b'.' => {
                let start = self.i;
                while self.i < self.s.len()
                    && (self.s[self.i].is_ascii_digit() || self.s[self.i] == b'.')
                {
                    self.i += 1;
                }
                let t = String::from_utf8_lossy(&self.s[start..self.i]).to_string();
                t.parse::<f64>()
                    .map_err(|_| format!("`{t}` is not a number"))
            }
            Some(c) if c.is_ascii_alphabetic() || c == b'_' => {
                let start = self.i;
                while self.i < self.s.len()
                    && (self.s[self.i].is_ascii_alphanumeric() || self.s[self.i] == b'_')
                {
                    self.i += 1;
                }
                let name = String::from_utf8_lossy(&self.s[start..self.i]).to_string();
                (self.angle)(&name)
                    .ok_or_else(|| format!("`{name}` is not a tier cut before this one"))
            }
            Some(c) => Err(format!("unexpected `{}`", c as char)),
            None => Err("the expression ends too soon".into()),
        }
    }
}
