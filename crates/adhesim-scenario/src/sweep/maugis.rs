//! The `maugis_parameter` pseudo-key: Maugis' parameter λ_M = 2σ0·(R/(πγ0K²))^(1/3),
//! K = 4E*/3, of a Dugdale law, turned into `adhesion.cohesive_stress` from the case's
//! indenter radius, contact modulus and work of adhesion (docs/sweeps.md).
//!
//! With a γ map (`adhesion.field`) σ0 is one number for the whole surface and δc = γ/σ0
//! follows the map; λ_M is then the parameter at the scenario's reference
//! `adhesion.work_of_adhesion`, as `derived.maugis_parameter` in summary.json reports it.

use crate::error::ScenarioError;
use crate::sweep::keys::{contact_modulus, get, number};
use adhesim::analysis::reference::cohesive_stress_for;
use anyhow::{bail, Result};

/// σ0 of Maugis' parameter `lambda` for the case's scenario `table` (after its other
/// overrides), refusing a law other than `dugdale` and a scenario without the inputs.
pub(super) fn cohesive_stress(table: &toml::Table, lambda: f64) -> Result<f64> {
    let why = "maugis_parameter";
    match get(table, "adhesion.law") {
        Some(toml::Value::String(law)) if law == "dugdale" => {}
        Some(other) => bail!(ScenarioError::invalid_as(
            "adhesion.law",
            other,
            "\"dugdale\" with maugis_parameter",
            format!(
                "maugis_parameter = {lambda} sets adhesion.cohesive_stress of law = \"dugdale\", but adhesion.law = {other}"
            )
        )),
        None => bail!(ScenarioError::missing(
            "adhesion.law",
            "\"dugdale\" with maugis_parameter",
            format!(
                "maugis_parameter = {lambda} sets adhesion.cohesive_stress of law = \"dugdale\", but adhesion.law is not set (the default is \"jkr\")"
            )
        )),
    }
    let radius = number(table, "indenter.radius", why)?;
    let contact_modulus = contact_modulus(table, why)?;
    let work_of_adhesion = number(table, "adhesion.work_of_adhesion", why)?;
    for (key, value) in [
        ("indenter.radius", radius),
        ("material.contact_modulus", contact_modulus),
        ("adhesion.work_of_adhesion", work_of_adhesion),
    ] {
        if !(value.is_finite() && value > 0.0) {
            bail!(ScenarioError::invalid_as(
                key,
                value,
                "> 0 with maugis_parameter",
                format!("maugis_parameter needs {key} > 0, got {value}")
            ));
        }
    }
    Ok(cohesive_stress_for(radius, contact_modulus, work_of_adhesion, lambda))
}

#[cfg(test)]
mod tests {
    use crate::sweep::plan::from_text;
    use std::path::Path;

    const BASE: &str = "[scenario]\n[scenario.grid]\nn = 32\nsize = 0.4\nboundary = \"free\"\n\
        [scenario.material]\ncontact_modulus = 2.0\n\
        [scenario.adhesion]\nwork_of_adhesion = 3e-4\nlaw = \"dugdale\"\ncohesive_stress = 0.5\n\
        [scenario.indenter]\nshape = \"sphere\"\nradius = 0.7\n\
        [scenario.protocol]\nkind = \"indent_pulloff\"\nmax_depth = 2e-3\nstep = 1e-4\n";

    fn plan(text: &str) -> anyhow::Result<crate::sweep::Plan> {
        from_text(text, "test.toml", Path::new("."), "test")
    }

    fn stress_of(case: &crate::sweep::Case) -> f64 {
        let table: toml::Table = case.scenario.parse().unwrap();
        table["adhesion"]["cohesive_stress"].as_float().unwrap()
    }

    /// σ0 = λ_M/2·(πγ0K²/R)^(1/3), K = 4E*/3, written out here independently of the
    /// library. Both sides are a handful of floating-point operations (one cube root),
    /// so they agree to a few ulps: the bound 1e-13 relative fails on any wrong factor
    /// or exponent (the smallest, a K without 4/3, is 21 % off).
    #[test]
    fn maugis_parameter_gives_the_closed_form_cohesive_stress() {
        let plan = plan(&format!("{BASE}[vary]\nmaugis_parameter = [0.3, 1.0, 3]\n")).unwrap();
        let (radius, modulus, gamma) = (0.7_f64, 2.0_f64, 3e-4_f64);
        let k = 4.0 * modulus / 3.0;
        for (case, lambda) in plan.cases.iter().zip([0.3, 1.0, 3.0]) {
            let expected = 0.5 * lambda * (std::f64::consts::PI * gamma * k * k / radius).cbrt();
            let got = stress_of(case);
            assert!(
                ((got - expected) / expected).abs() < 1e-13,
                "λ_M = {lambda}: σ0 {got} vs {expected}"
            );
            assert_eq!(case.values, vec![lambda.to_string()]);
        }
    }

    /// The shorthand is applied after the case's other keys: the work of adhesion and the
    /// contact modulus of the same case (here from Young's modulus and Poisson's ratio,
    /// E* = E/(1 − ν²)) enter σ0.
    #[test]
    fn maugis_parameter_uses_the_case_values() {
        let text = BASE.replace("contact_modulus = 2.0", "youngs_modulus = 1.5\npoisson_ratio = 0.5");
        let text =
            format!("{text}[zip]\n\"adhesion.work_of_adhesion\" = [1e-4, 8e-4]\nmaugis_parameter = [2.0, 2.0]\n");
        let plan = plan(&text).unwrap();
        let k = 4.0 * (1.5 / 0.75) / 3.0;
        for (case, gamma) in plan.cases.iter().zip([1e-4_f64, 8e-4]) {
            let expected = (std::f64::consts::PI * gamma * k * k / 0.7).cbrt();
            assert!(((stress_of(case) - expected) / expected).abs() < 1e-13);
        }
        // Eight times γ0: twice σ0 at the same λ_M.
        assert!((stress_of(&plan.cases[1]) / stress_of(&plan.cases[0]) - 2.0).abs() < 1e-13);
    }

    fn error_of(text: &str) -> String {
        format!("{:#}", plan(text).expect_err("the sweep must be refused"))
    }

    #[test]
    fn bad_maugis_parameters_are_refused_naming_the_key_and_value() {
        for (value, fragment) in [
            ("0.0", "maugis_parameter must be a finite number > 0, got 0"),
            ("-1.0", "maugis_parameter must be a finite number > 0, got -1"),
            ("inf", "maugis_parameter must be a finite number > 0, got inf"),
            ("nan", "maugis_parameter must be a finite number > 0, got NaN"),
            ("\"big\"", "maugis_parameter must be a number, got \"big\""),
        ] {
            let error = error_of(&format!("{BASE}[vary]\nmaugis_parameter = [1.0, {value}]\n"));
            assert!(error.contains(fragment), "{value}: {error}");
        }
        for (law, fragment) in [
            ("\"jkr\"", "but adhesion.law = \"jkr\""),
            ("\"exponential\"\nrange = 1e-3", "but adhesion.law = \"exponential\""),
        ] {
            let text = BASE.replace("\"dugdale\"\ncohesive_stress = 0.5", law);
            let error = error_of(&format!("{text}[vary]\nmaugis_parameter = [1.5]\n"));
            assert!(
                error.contains("maugis_parameter = 1.5 sets adhesion.cohesive_stress"),
                "{error}"
            );
            assert!(error.contains(fragment), "{error}");
        }
        let text = BASE.replace("law = \"dugdale\"\ncohesive_stress = 0.5\n", "");
        let error = error_of(&format!("{text}[vary]\nmaugis_parameter = [1.5]\n"));
        assert!(error.contains("adhesion.law is not set"), "{error}");
        // Typed for Python: the key at fault is the law.
        let typed = crate::error::ScenarioError::from_anyhow(
            plan(&format!("{text}[vary]\nmaugis_parameter = [1.5]\n")).expect_err("refused"),
        );
        assert_eq!(typed.key.as_deref(), Some("adhesion.law"), "{typed}");
        // The law may come from the sweep itself.
        let sweep = plan(&format!(
            "{text}[set]\n\"adhesion.law\" = \"dugdale\"\n[vary]\nmaugis_parameter = [1.5]\n"
        ));
        assert!(sweep.is_ok(), "{:?}", sweep.err());
        let error = error_of(&format!(
            "{BASE}[set]\n\"adhesion.cohesive_stress\" = 0.2\n[vary]\nmaugis_parameter = [1.5]\n"
        ));
        assert!(error.contains("adhesion.cohesive_stress"), "{error}");
        assert!(error.contains("maugis_parameter"), "{error}");
        let typed = crate::error::ScenarioError::from_anyhow(
            plan(&format!(
                "{BASE}[set]\n\"adhesion.cohesive_stress\" = 0.2\n[vary]\nmaugis_parameter = [1.5]\n"
            ))
            .expect_err("refused"),
        );
        assert_eq!(
            (typed.key.as_deref(), typed.value.as_deref()),
            (Some("adhesion.cohesive_stress"), Some("0.2")),
            "{typed}"
        );
    }
}
