//! The sections a generated model carries beside its energies: holonomic
//! constraints, unilateral contacts and control inputs (forces are in the
//! parent, with the positions they act along).

use super::Gen;

impl Gen<'_> {
    /// `constraints:` of a coordinate against an expression in t and q,
    /// sometimes indexed over an indexed coordinate's elements.
    pub(super) fn constraints(&mut self) -> String {
        let mut entries = Vec::new();
        for name in ["c1", "c2"].iter().take(self.rng.range(1, 2)) {
            let c = self.rng.pick(&self.scope.coordinates).clone();
            let (head, target) = match &c.len {
                Some((len_text, _)) if self.rng.chance(0.5) => (
                    format!("{name}[i in 0..{len_text}]"),
                    format!("{}[i]", c.name),
                ),
                _ => (name.to_string(), self.reference(&c)),
            };
            let d = self.depth();
            let value = self.expr(d, false);
            entries.push(match self.rng.below(3) {
                0 => format!("{head}: {target} - {value}"),
                1 => format!("{head}: {target}^2 = {value}"),
                _ => format!("{head}: {target} = {value}"),
            });
        }
        format!("constraints: {};", entries.join(", "))
    }

    /// `contacts:` of a coordinate against an expression in t and q, each
    /// with or without a law (restitution, friction with a slip velocity),
    /// or without a gap (friction against a given normal force):
    /// the coefficients are drawn as any expression, so some depend on the
    /// state, one of the spanned errors the checks give.
    pub(super) fn contacts(&mut self) -> String {
        let mut entries = Vec::new();
        for name in ["k1", "k2"].iter().take(self.rng.range(1, 2)) {
            let c = self.rng.pick(&self.scope.coordinates).clone();
            let target = self.reference(&c);
            if self.rng.chance(0.2) {
                // Without a gap: friction against a given normal force.
                let normal = self.expr(1, false);
                let mu = self.expr(1, false);
                entries.push(format!(
                    "{name}: {{ normal: {normal}, friction: {mu}, slip: dot({target}) }}"
                ));
                continue;
            }
            let d = self.depth();
            let bound = self.expr(d, false);
            let op = if self.rng.chance(0.5) { ">=" } else { "<=" };
            let mut law = Vec::new();
            if self.rng.chance(0.5) {
                law.push(format!("restitution: {}", self.expr(1, false)));
            }
            if self.rng.chance(0.4) {
                let s = self.rng.pick(&self.scope.coordinates).clone();
                let slip = format!("dot({})", self.reference(&s));
                law.push(format!("friction: {}", self.expr(1, false)));
                law.push(format!("slip: {slip}"));
            }
            let law = if law.is_empty() {
                String::new()
            } else {
                format!(" {{ {} }}", law.join(", "))
            };
            entries.push(format!("{name}: {target} {op} {bound}{law}"));
        }
        format!("contacts: {};", entries.join(", "))
    }

    /// `inputs:` (scalar or indexed) and a force on a coordinate scaled by
    /// one of them: a motor. The force section is its own, so it may clash
    /// with another force on the same target (one spanned error).
    pub(super) fn inputs(&mut self) -> String {
        let c = self.rng.pick(&self.scope.coordinates).clone();
        let target = self.reference(&c);
        let d = self.depth();
        let gain = self.expr(d, false);
        if self.rng.chance(0.5) {
            format!("inputs: u_in; forces: {target} = u_in*({gain});")
        } else {
            format!("inputs: w_in[2]; forces: {target} = w_in[0] + w_in[1]*({gain});")
        }
    }
}
