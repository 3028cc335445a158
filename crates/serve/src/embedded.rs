//! The browser front end built into the binary (by `build.rs`, from
//! `web/dist`), so that the modeler is served from any working directory
//! and from an installed or copied binary.

include!(concat!(env!("OUT_DIR"), "/embedded_web.rs"));

/// The embedded file at `relative` (a path under `web/dist`, with `/`).
pub fn file(relative: &str) -> Option<&'static [u8]> {
    FILES
        .binary_search_by(|(path, _)| (*path).cmp(relative))
        .ok()
        .map(|i| FILES[i].1)
}

/// Whether the front end was built when this binary was.
pub fn is_present() -> bool {
    file("index.html").is_some()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_sorted_for_binary_search() {
        assert!(FILES.windows(2).all(|w| w[0].0 < w[1].0));
    }

    #[test]
    fn an_embedded_front_end_has_its_page_and_every_asset_it_names() {
        let Some(page) = file("index.html") else {
            println!("SKIP: the front end was not built with this binary (no npm at build time)");
            return;
        };
        let page = String::from_utf8_lossy(page);
        // Every local script and stylesheet the page loads (Vite writes
        // them relative, `./assets/...`) is embedded.
        let mut named = 0;
        for attribute in ["src=\"./", "href=\"./"] {
            for piece in page.split(attribute).skip(1) {
                let path = piece.split('"').next().unwrap_or("");
                assert!(
                    file(path).is_some(),
                    "{path} is named by index.html but not embedded"
                );
                named += 1;
            }
        }
        assert!(
            named >= 2,
            "index.html names {named} local assets; expected its script and styles"
        );
    }
}
