//! Source text → [`ast::File`], with the grammar in `grammar/scen.pest`.
//!
//! [`parse`] is the entry point (`parser.rs`): the file is split into
//! statement chunks (`scanner.rs`), pest parses each chunk, its pairs become
//! AST nodes (`builder.rs`, and `expr.rs` for `expect` expressions), and
//! pest's errors become readable diagnostics (`syntax_error.rs`).

pub mod ast;
mod builder;
mod calc;
mod expr;
mod parser;
mod scanner;
mod syntax_error;
#[cfg(test)]
mod testing;

pub use builder::UNIT_WORDS;
pub use parser::parse;
pub use scanner::{
    EXPRESSION_WORDS, FAMILY_VALUE_WORDS, GRID_OPTION_KEYWORDS, Lexer, MOVING_KEYWORDS,
    ROBOT_CLAUSE_KEYWORDS, ROBOT_SHAPE_KEYWORDS, STATEMENT_KEYWORDS, TEAM_KEYWORDS, Token,
    TokenKind, WORLD_ITEM_KEYWORDS, statement_at,
};
