//! The page of the workbench, embedded in the binary: `page.html`, `page.js`, `plan.js` (the
//! rough-planning panel), `recipe.js` (the tier editor) and `page.css` beside this file, served at `/`, `/page.js`,
//! `/plan.js`, `/recipe.js` and `/page.css` (no build step, no network).

use axum::http::header;
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;

const PAGE_HTML: &str = include_str!("page.html");
const PAGE_JS: &str = include_str!("page.js");
const PAGE_CSS: &str = include_str!("page.css");
const PLAN_JS: &str = include_str!("plan.js");
const RECIPE_JS: &str = include_str!("recipe.js");

/// The page's routes.
pub fn routes<S: Clone + Send + Sync + 'static>() -> Router<S> {
    Router::new()
        .route(
            "/",
            get(|| async { asset("text/html; charset=utf-8", PAGE_HTML) }),
        )
        .route(
            "/page.js",
            get(|| async { asset("text/javascript; charset=utf-8", PAGE_JS) }),
        )
        .route(
            "/plan.js",
            get(|| async { asset("text/javascript; charset=utf-8", PLAN_JS) }),
        )
        .route(
            "/recipe.js",
            get(|| async { asset("text/javascript; charset=utf-8", RECIPE_JS) }),
        )
        .route(
            "/page.css",
            get(|| async { asset("text/css; charset=utf-8", PAGE_CSS) }),
        )
}

fn asset(kind: &'static str, body: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, kind),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        body,
    )
        .into_response()
}

#[cfg(test)]
mod tests {
    use super::PAGE_HTML;

    /// Every `id` on the page is unique: a second element with an id makes
    /// `querySelector` return the first, and a script then writes into the wrong element
    /// (the plan panel's Stones input and its stones table once shared one).
    #[test]
    fn the_page_ids_are_unique() {
        let mut seen = std::collections::BTreeSet::new();
        let mut count = 0;
        for part in PAGE_HTML.split(" id=\"").skip(1) {
            let id = part.split('"').next().unwrap();
            assert!(seen.insert(id), "id `{id}` appears twice in page.html");
            count += 1;
        }
        assert!(count > 20, "only {count} ids found: the scan is broken");
    }
}
