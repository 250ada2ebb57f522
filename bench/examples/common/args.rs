//! The examples' positional arguments: parsed, defaulted, or the example stopped with a message.

/// Prints `message` as the example `name`'s and exits with status 2.
pub fn fail(name: &str, message: String) -> ! {
    eprintln!("{name}: {message}");
    std::process::exit(2)
}

/// Argument `k` (`what`, for the message) of the example `name`, or `default` when absent.
pub fn arg<T: std::str::FromStr>(name: &str, args: &[String], k: usize, what: &str, default: Option<T>) -> T {
    match (args.get(k), default) {
        (Some(text), _) => text
            .parse()
            .unwrap_or_else(|_| fail(name, format!("argument {k} ({what}): {text:?} is not valid"))),
        (None, Some(d)) => d,
        (None, None) => fail(name, format!("argument {k} ({what}) is missing; see the example's comment")),
    }
}
