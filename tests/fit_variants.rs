//! The variant fixtures (`tests/fixtures/variants/<model>/`) are valid `--vary` files of
//! their example: the same program with other numbers, and the same parts.

use std::path::PathBuf;

#[test]
fn variants_match_their_models() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("tests/fixtures/variants");
    let mut count = 0;
    for model in std::fs::read_dir(&dir).unwrap() {
        let model = model.unwrap().path();
        if !model.is_dir() {
            continue;
        }
        let name = model.file_name().unwrap().to_string_lossy().into_owned();
        let base_path = root.join("examples").join(format!("{name}.scad"));
        let mut sources = reparamc::front::source::SourceMap::new();
        let (loaded, base) = reparamc::load_model_parsed(&mut sources, &base_path).unwrap();
        let mut variants = 0;
        for v in std::fs::read_dir(&model).unwrap() {
            let v = v.unwrap().path();
            if v.extension().is_none_or(|e| e != "scad") {
                continue;
            }
            let var =
                reparamc::variation::load_variation(&mut sources, loaded.main, &base.model, &v)
                    .unwrap_or_else(|d| panic!("{}: {}", v.display(), d.render_plain(&sources)));
            assert_eq!(var.values.len(), base.model.slots.len(), "{}", v.display());
            let mut s2 = reparamc::front::source::SourceMap::new();
            let own = reparamc::load_model(&mut s2, &v).unwrap().model;
            assert_eq!(own.parts.len(), base.model.parts.len(), "{}", v.display());
            assert!(
                own.parts.iter().all(|p| {
                    let g = reparamc::render::scene::PartGeom::from_part(p);
                    g.valid
                }),
                "{}: a degenerate part",
                v.display()
            );
            variants += 1;
        }
        assert!(variants >= 4, "{name}: only {variants} variants");
        count += variants;
    }
    assert!(count >= 40);
}
