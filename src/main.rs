fn main() {
    std::process::exit(csgrt::cli::main());
}
