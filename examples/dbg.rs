fn main() {
    let paths: Vec<std::path::PathBuf> = std::env::args().skip(1).map(Into::into).collect();
    let reports = rigor::check::check_paths(&paths, &rigor::check::Options::default());
    for r in &reports {
        println!("== {} ok={} input_error={} links={} verified={}", r.path, r.ok(), r.input_error, r.links(), r.verified());
        for d in &r.diagnostics {
            print!("{}", rigor::diag::render(d, &r.path, &r.source));
        }
    }
}
