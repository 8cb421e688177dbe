//! Source text → [`ast::File`], with the grammar in `grammar/scen.pest`.

pub mod ast;
mod parser;

pub use parser::parse;
