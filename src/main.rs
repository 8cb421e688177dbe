//! `scen`: exit codes only; everything else is in the library.

fn main() {
    std::process::exit(scen::main());
}
