//! The precedence table of expressions, as the grammar (`grammar/openscad.pest`) writes it:
//! its levels and its binary operators, by rule. The builder folds chains with it, and the
//! error messages name what a rule expected with it; nothing else restates it.

use super::Rule;
use crate::front::ast::BinaryOp;

/// Whether `rule` is a precedence level of expressions, lowest first: `expr` (the
/// `function`/`let`/`assert`/`echo` prefixes), `?:`, `||`, `&&`, `== !=`, `< <= > >=`,
/// `+ -`, `* / %`, unary `- + !` with `^`, postfix call / index / member. A level holding
/// a single child is that child.
pub(super) fn is_level(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::expr
            | Rule::ternary
            | Rule::or_expr
            | Rule::and_expr
            | Rule::eq_expr
            | Rule::rel_expr
            | Rule::add_expr
            | Rule::mul_expr
            | Rule::unary
            | Rule::postfix
    )
}

/// The binary operator a rule stands for (`^` included: it is folded with the prefix
/// operators of the `unary` level, to the right).
pub(super) fn binary_op(rule: Rule) -> Option<BinaryOp> {
    Some(match rule {
        Rule::op_or => BinaryOp::Or,
        Rule::op_and => BinaryOp::And,
        Rule::op_eq => BinaryOp::Eq,
        Rule::op_ne => BinaryOp::Ne,
        Rule::op_le => BinaryOp::Le,
        Rule::op_ge => BinaryOp::Ge,
        Rule::op_lt => BinaryOp::Lt,
        Rule::op_gt => BinaryOp::Gt,
        Rule::op_add => BinaryOp::Add,
        Rule::op_sub => BinaryOp::Sub,
        Rule::op_mul => BinaryOp::Mul,
        Rule::op_div => BinaryOp::Div,
        Rule::op_mod => BinaryOp::Mod,
        Rule::op_pow => BinaryOp::Pow,
        _ => return None,
    })
}
