//! `zline scan`: the edge table and the active edge list of a triangle
//! checked by hand, text and JSON, and bad triangles.

use crate::{check_clean_error, zline};

#[test]
fn a_triangle_checked_by_hand_prints_its_edge_table_and_spans() {
    let out = zline(&["scan", "--triangle", "0,0,0 0,4,0 4,0,1"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for line in [
        "  long        0      4      0.0000   0.0000",
        "  lower       0      4      3.5000  -1.0000",
        "  y    0: AEL [long 0.0000, lower 3.5000]  span 0..3  z 0.125000 .. 0.625000",
        "  y    3: AEL [long 0.0000, lower 0.5000]  no sample",
    ] {
        assert!(text.contains(line), "{line:?} in\n{text}");
    }
    let out = zline(&["scan", "--triangle", "0,0,0 0,4,0 4,0,1", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["rows"][1]["span"], serde_json::json!([0, 2]));
    assert_eq!(json["edges"][1]["inverse_slope"], -1.0);
    check_clean_error(&zline(&["scan", "--triangle", "0,0,0 1,1,0"]), &["9 numbers"]);
    check_clean_error(&zline(&["scan", "--triangle", "0,0,0 1,1,0 2,2,0"]), &["zero area"]);
    check_clean_error(&zline(&["scan", "--triangle", "0,0,0 1,x,0 2,2,0"]), &["'x' is not a number"]);
}

#[test]
fn a_models_triangle_is_traced_where_the_camera_sees_it() {
    let bunny = crate::repo().join("assets/ply/bunny_lowres.ply");
    let path = bunny.to_str().unwrap();
    let out = zline(&["scan", path, "--index", "100", "--size", "200x150", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // Inside the 200 × 150 window, with at least one covered span.
    for v in json["vertices"].as_array().unwrap() {
        let (x, y) = (v[0].as_f64().unwrap(), v[1].as_f64().unwrap());
        assert!((0.0..200.0).contains(&x) && (0.0..150.0).contains(&y), "{v}");
    }
    assert!(json["rows"].as_array().unwrap().iter().any(|r| !r["span"].is_null()));
    check_clean_error(
        &zline(&["scan", path, "--index", "999999"]),
        &["no triangle 999999", "6598 triangles"],
    );
    check_clean_error(&zline(&["scan", path, "--object", "3"]), &["no object 3"]);
}

/// A headless Chromium, when one is installed.
fn chromium() -> Option<&'static str> {
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find(|c| std::process::Command::new(c).arg("--version").output().is_ok_and(|o| o.status.success()))
}

#[test]
fn the_html_page_steps_through_the_same_rows_in_headless_chromium() {
    let dir = tempfile::tempdir().unwrap();
    let (html, png) = (dir.path().join("scan.html"), dir.path().join("scan.png"));
    let triangle = "1.2,0.3,0.1 7.7,2.9,0.5 3.1,6.6,0.9";
    let args = ["scan", "--triangle", triangle, "--size", "16x16", "--html", html.to_str().unwrap()];
    let out = zline(&[&args[..], &["--image", png.to_str().unwrap()]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    // The drawing: 16 pixels a window pixel around the triangle's box.
    let img = image::open(&png).unwrap();
    assert_eq!((img.width() % 16, img.height() % 16), (0, 0));
    let Some(browser) = chromium() else {
        eprintln!("skipped: no headless Chromium (Debian's chromium) installed");
        return;
    };
    // Each step k, opened as #step=k, shows row k − 1 as the text shows it.
    let rows: Vec<&str> = text.lines().filter(|l| l.trim_start().starts_with("y ")).collect();
    assert_eq!(rows.len(), 7);
    for (k, row) in rows.iter().enumerate() {
        let url = format!("file://{}#step={}", html.display(), k + 1);
        let dom = std::process::Command::new(browser)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--virtual-time-budget=2000",
                "--dump-dom",
                &url,
            ])
            .output()
            .unwrap();
        let dom = String::from_utf8_lossy(&dom.stdout);
        let shown = dom.split("<div id=\"row\">").nth(1).and_then(|s| s.split("</div>").next()).unwrap_or("");
        let want = row.trim_start().replace("AEL", "").split_whitespace().collect::<Vec<_>>().join(" ");
        let got = shown.replace("AEL", "").split_whitespace().collect::<Vec<_>>().join(" ");
        assert_eq!(got, want, "step {}", k + 1);
        assert!(dom.contains(&format!("step {} of 7", k + 1)), "step {}", k + 1);
    }
}
