//! docs/robot-model.md lists the calibrated error model as `ilmr_sim::profile` has it.

#[test]
fn robot_model_md_lists_the_calibrated_profile() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/robot-model.md");
    let doc = std::fs::read_to_string(&path).expect("docs/robot-model.md readable");
    let table = ilmr_sim::profile::markdown_table();
    assert!(
        doc.contains(&table),
        "docs/robot-model.md's table of the calibrated profile differs from \
         ilmr_sim::profile::CALIBRATED; it should read:\n{table}"
    );
    for p in ilmr_sim::SimProfile::ALL {
        assert!(
            doc.contains(&format!("`{}`", p.name())),
            "{} documented",
            p.name()
        );
    }
}
