//! Tests of the projections (`project`): kept apart to keep the module's own file short.

use super::*;

/// What projecting `x` onto `row` costs in `metric`.
fn cost(faces: &Faces, metric: Metric, x: &[f64], row: &Affine) -> f64 {
    let basis = RowBasis::default();
    let mut blocks = SlotBlocks::of(faces);
    let members = blocks.members();
    Projector::new(metric)
        .shift_and_cost(faces, &basis, &mut blocks, &members, x, &[row])
        .1
}

/// One number sizes five boards, another one board; a variation moves the first by one
/// unit, breaking "the two are equal" by one unit.
#[test]
fn a_typed_number_weighs_its_leverage_not_the_faces_it_drives() {
    let m = crate::front::test_model(
        "w = 30;\nv = 30;\n\
         for (i = [0:4]) translate([i * 40, 0, 0]) cube([w, 10, 10]);\n\
         translate([0, 50, 0]) cube([v, 10, 10]);\n",
    );
    let faces = Faces::of(&m);
    let slot = |name: &str| {
        m.slots
            .iter()
            .position(|s| s.name == name)
            .unwrap_or_else(|| panic!("no slot {name}")) as SlotId
    };
    let (w, v) = (slot("w"), slot("v"));
    let row = Affine {
        constant: 0.0,
        terms: vec![(w, 1.0), (v, -1.0)],
    };
    let mut x = m.slot_values();
    x[w as usize] += 1.0;
    // Typed: two numbers each off by noise of σ, so the residual's variance is 2σ² and
    // its cost 1/2, however many boards `w` sizes (in the faces' metric, `w` would count
    // once per board).
    let typed = cost(&faces, faces.number_metric(&[]), &x, &row);
    assert!((typed - 0.5).abs() < 1e-6, "{typed}");
    // A variation without the five boards leaves `w` no leverage: moving it costs nothing.
    let without: Vec<usize> = (0..5).collect();
    let free = cost(&faces, faces.number_metric(&without), &x, &row);
    assert!(free < 1e-6, "{free}");
}

/// Four boards under a top, all one block: its faces, metric, a basis of one chosen row
/// inside the block (so its null space is not the identity) and every slot.
fn boards_under_a_top() -> (Faces, Metric, RowBasis, Vec<SlotId>) {
    let m = crate::front::test_model(
        "for (i = [0:3]) translate([i * 12, 0, 0]) cube([10, 10 + i, 5]);\n\
         translate([0, 0, 5]) cube([46, 14, 2]);\n",
    );
    let faces = Faces::of(&m);
    let mut basis = RowBasis::default();
    basis.add(&Affine {
        constant: 0.0,
        terms: vec![(0, 1.0), (1, -1.0)],
    });
    let slots: Vec<SlotId> = (0..m.slots.len() as SlotId).collect();
    let metric = faces.metric(&m.slot_values(), &[]);
    (faces, metric, basis, slots)
}

/// A block serves the same columns `K nᵀ` whether it solves for each or reads them from
/// the dense `K` it makes once it has served as many as it has slots.
#[test]
fn dense_columns_are_the_solved_ones() {
    let (faces, metric, basis, slots) = boards_under_a_top();
    let block = Block::build(&faces, &metric, &basis, slots.clone());
    let rows: Vec<Affine> = slots
        .windows(2)
        .map(|w| Affine {
            constant: 0.0,
            terms: vec![(w[0], 1.0), (w[1], -0.5)],
        })
        .collect();
    let solved: Vec<Vec<f64>> = rows.iter().map(|r| block.k_column(r)).collect();
    assert!(block.dense.get().is_none(), "fewer columns than slots");
    for _ in 0..slots.len() {
        block.k_column(&rows[0]);
    }
    assert!(
        block.dense.get().is_some(),
        "made once it has served enough"
    );
    let scale = solved.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    for (r, want) in rows.iter().zip(&solved) {
        for (got, want) in block.k_column(r).iter().zip(want) {
            assert!((got - want).abs() <= 1e-9 * scale, "{got} vs {want}");
        }
    }
    // Rows absorbed afterwards: folded into the dense `K` here, kept as corrections in a
    // block without one; both serve the same columns.
    let mut block = block;
    let mut sparse = Block::build(&faces, &metric, &basis, slots.clone());
    for r in &rows[1..4] {
        block.absorb(r);
        sparse.absorb(r);
    }
    assert!(block.corrections.is_empty() && sparse.dense.get().is_none());
    assert_eq!((block.absorbed, sparse.corrections.len()), (3, 3));
    // The costs read off the dense `K` at the rows' slots are those of whole columns,
    // with corrections folded in (`block`) or kept beside a `K` made after them (`sparse`).
    let pairs: Vec<(&Affine, &Affine)> = rows[4..].iter().zip(&rows[5..]).collect();
    let want: Vec<f64> = pairs
        .iter()
        .map(|(a, b)| sparse.dot(a, &sparse.k_column(b)))
        .collect();
    for _ in 0..slots.len() {
        sparse.k_column(&rows[0]);
    }
    let k = block.dense.get().expect("still dense").clone();
    let k_sparse = sparse
        .dense
        .get()
        .expect("made after the corrections")
        .clone();
    assert_eq!(sparse.corrections.len(), 3);
    for ((a, b), want) in pairs.iter().zip(&want) {
        let form = |blk: &Block, k: &DMatrix<f64>| {
            blk.k_form_of(k, &blk.row_in_block(a), &blk.row_in_block(b))
        };
        for got in [form(&block, &k), form(&sparse, &k_sparse)] {
            assert!((got - want).abs() <= 1e-9 * scale, "{got} vs {want}");
        }
    }
    for r in &rows[4..] {
        for (got, want) in block.k_column(r).iter().zip(sparse.k_column(r)) {
            assert!((got - want).abs() <= 1e-9 * scale, "{got} vs {want}");
        }
    }
}

/// A Gram matrix made by forward substitutions alone (a block without a dense `K`) is the
/// one whole columns give, corrections included, and the block counts its rows as served:
/// once that makes the dense `K`, the forward path steps aside.
#[test]
fn forward_gram_is_the_columns_gram() {
    let (faces, metric, basis, slots) = boards_under_a_top();
    let rows: Vec<Affine> = slots
        .windows(3)
        .map(|w| Affine {
            constant: 0.0,
            terms: vec![(w[0], 1.0), (w[2], -0.5)],
        })
        .collect();
    let mut block = Block::build(&faces, &metric, &basis, slots.clone());
    for r in &rows[..2] {
        block.absorb(r);
    }
    assert_eq!(block.corrections.len(), 2);
    let picked: Vec<&Affine> = rows[2..6].iter().collect();
    let want: Vec<Vec<f64>> = picked
        .iter()
        .map(|a| {
            let col = block.k_column(a);
            picked.iter().map(|b| block.dot(b, &col)).collect()
        })
        .collect();
    let mut got = DMatrix::zeros(picked.len(), picked.len());
    assert!(block.forward_gram(&picked, &mut got), "no dense K yet");
    let scale = want.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    for (i, row) in want.iter().enumerate() {
        for (j, w) in row.iter().enumerate() {
            assert!(
                (got[(i, j)] - w).abs() <= 1e-9 * scale,
                "{} vs {w}",
                got[(i, j)]
            );
        }
    }
    while block.dense.get().is_none() {
        if !block.forward_gram(&picked, &mut got) {
            break;
        }
    }
    assert!(
        block.dense.get().is_some(),
        "made once it has served enough"
    );
    assert!(!block.forward_gram(&picked, &mut got));
}
