//! Prints a few samples of some warps with their pdfs.
fn main() {
    println!("mcrt: (placeholder until the warps land)");
}
