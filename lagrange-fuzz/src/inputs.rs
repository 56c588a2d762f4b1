//! The input stream: input `index` under `seed` is a pure function of the
//! two (and of the corpus of repository models), drawn from a fixed mix of
//! generated models, the repository's models, their mutants and the
//! pathological families.

use crate::rng::Rng;
use crate::{families, generate, mutate};

include!(concat!(env!("OUT_DIR"), "/corpus.rs"));

/// One input: the model's source and where it came from.
#[derive(Clone, Debug)]
pub struct Input {
    pub text: String,
    /// `generated`, `corpus 12`, `mutated corpus 12: wrap+number`,
    /// `flat-sum n=120`, ...
    pub origin: String,
}

impl Input {
    /// The origin's first word: what the summary groups findings by.
    pub fn kind(&self) -> &str {
        self.origin.split([' ', ':']).next().unwrap_or("")
    }
}

/// Shares of the mix, in per mille: generated models, repository models as
/// written, mutants, pathological families.
const MIX: [u32; 4] = [380, 20, 560, 40];

pub fn input(seed: u64, index: u64) -> Input {
    let mut rng = Rng::for_input(seed, index);
    match rng.weighted(&MIX) {
        0 => Input {
            text: generate::model(&mut rng),
            origin: "generated".into(),
        },
        1 => {
            let k = rng.below(CORPUS.len());
            Input {
                text: CORPUS[k].into(),
                origin: format!("corpus {k}"),
            }
        }
        2 => {
            let (base, base_origin) = mutation_base(&mut rng);
            let (donor, _) = mutation_base(&mut rng);
            let (text, ops) = mutate::mutate(&mut rng, &base, &donor);
            Input {
                text,
                origin: format!("mutated {base_origin}: {ops}"),
            }
        }
        _ => {
            let (origin, text) = families::family(&mut rng);
            Input { text, origin }
        }
    }
}

/// A model to mutate: generated or from the repository, half and half.
fn mutation_base(rng: &mut Rng) -> (String, String) {
    if rng.chance(0.5) {
        (generate::model(rng), "generated".into())
    } else {
        let k = rng.below(CORPUS.len());
        (CORPUS[k].into(), format!("corpus {k}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_corpus_holds_the_repository_models() {
        assert!(CORPUS.len() > 50, "{} models", CORPUS.len());
        assert!(CORPUS.iter().any(|m| m.contains("DoublePendulum")));
    }

    #[test]
    fn an_input_is_a_function_of_seed_and_index() {
        for index in 0..50 {
            assert_eq!(input(9, index).text, input(9, index).text);
        }
        let differ = (0..50).filter(|&i| input(9, i).text != input(10, i).text);
        assert!(differ.count() > 40);
    }
}
