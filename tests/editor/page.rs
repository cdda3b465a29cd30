//! The editor page as a test sees it: what it shows (read through `body[data-*]`, the
//! attributes the page keeps for tests) and what a person does to it (pointer and keys,
//! through WebDriver actions in viewport pixels).

use std::time::{Duration, Instant};

use fantoccini::actions::{
    InputSource, KeyAction, KeyActions, MOUSE_BUTTON_LEFT, MouseActions, PointerAction,
    TouchActions, WheelAction, WheelActions,
};
use fantoccini::key::Key;
use fantoccini::{Client, Locator};
use serde_json::{Value, json};

/// How long the page may take to settle after an action.
const SETTLE: Duration = Duration::from_secs(15);

/// The editor open in a browser.
pub struct Page<'a> {
    pub client: &'a Client,
}

impl<'a> Page<'a> {
    /// Opens `GET /` of the server at `address` and waits until the sample is drawn.
    pub async fn open(client: &'a Client, address: &str) -> Page<'a> {
        client
            .goto(&format!("{address}/"))
            .await
            .expect("open the editor");
        let page = Page { client };
        page.wait_until(
            "the page is ready",
            "document.body.dataset.ready === 'true'",
        )
        .await;
        page.settle().await;
        page
    }

    /// Runs `script` (a function body) with `args` and returns its value.
    pub async fn run(&self, script: &str, args: Vec<Value>) -> Value {
        self.client
            .execute(script, args)
            .await
            .unwrap_or_else(|error| panic!("script failed: {error}\n{script}"))
    }

    /// Polls `condition` (an expression) until true; panics naming `what` after a while.
    pub async fn wait_until(&self, what: &str, condition: &str) {
        let deadline = Instant::now() + SETTLE;
        let script = format!("return Boolean({condition});");
        loop {
            if self.run(&script, vec![]).await == json!(true) {
                return;
            }
            assert!(
                Instant::now() < deadline,
                "timed out waiting until {what}; page state: {}",
                self.describe().await
            );
            tokio::time::sleep(Duration::from_millis(15)).await;
        }
    }

    /// Waits until no request of the page is in flight and no drag is going on.
    pub async fn settle(&self) {
        self.wait_until(
            "the page is idle",
            "document.body.dataset.busy !== 'true' && document.body.dataset.dragging !== 'true'",
        )
        .await;
    }

    /// `body[data-name]`, "" when absent.
    pub async fn data(&self, name: &str) -> String {
        let value = self
            .run(
                "return document.body.dataset[arguments[0]] || '';",
                vec![json!(name)],
            )
            .await;
        value.as_str().unwrap_or_default().to_owned()
    }

    /// The committed curve (`body[data-curve]`).
    pub async fn curve(&self) -> Value {
        serde_json::from_str(&self.data("curve").await).expect("data-curve is JSON")
    }

    /// The picked point `{parameter, point}`, when there is one.
    pub async fn picked(&self) -> Option<Value> {
        let text = self.data("picked").await;
        (!text.is_empty()).then(|| serde_json::from_str(&text).unwrap())
    }

    /// Everything the page's error hook caught (script errors, console errors, CSP).
    pub async fn script_errors(&self) -> Vec<String> {
        let value = self
            .run("return window.editorErrors || ['no error hook'];", vec![])
            .await;
        serde_json::from_value(value).unwrap()
    }

    /// A summary for failure messages.
    pub async fn describe(&self) -> String {
        let value = self
            .run(
                "const d = document.body.dataset; return JSON.stringify({busy: d.busy, \
                 dragging: d.dragging, message: d.message, error: d.error, picked: d.picked, \
                 errors: window.editorErrors});",
                vec![],
            )
            .await;
        value.as_str().unwrap_or_default().to_owned()
    }

    /// Viewport pixels of the curve point `point`, rounded to whole pixels (WebDriver
    /// moves the pointer by whole pixels).
    pub async fn to_screen(&self, point: [f64; 2]) -> (i64, i64) {
        let value = self
            .run(
                "const m = document.getElementById('scene').getScreenCTM(); \
                 const p = new DOMPoint(arguments[0], arguments[1]).matrixTransform(m); \
                 return [p.x, p.y];",
                vec![json!(point[0]), json!(point[1])],
            )
            .await;
        let [x, y] = [value[0].as_f64().unwrap(), value[1].as_f64().unwrap()];
        (x.round() as i64, y.round() as i64)
    }

    /// The curve point under viewport pixel `pixel`, computed as the page computes it.
    pub async fn to_curve(&self, pixel: (i64, i64)) -> [f64; 2] {
        let value = self
            .run(
                "const m = document.getElementById('scene').getScreenCTM().inverse(); \
                 const p = new DOMPoint(arguments[0], arguments[1]).matrixTransform(m); \
                 return [p.x, p.y];",
                vec![json!(pixel.0), json!(pixel.1)],
            )
            .await;
        [value[0].as_f64().unwrap(), value[1].as_f64().unwrap()]
    }

    /// A click (down and up) at `pixel`.
    pub async fn click_at(&self, pixel: (i64, i64)) {
        let mouse = MouseActions::new("mouse".to_owned())
            .then(move_to(pixel))
            .then(PointerAction::Down {
                button: MOUSE_BUTTON_LEFT,
            })
            .then(PointerAction::Up {
                button: MOUSE_BUTTON_LEFT,
            });
        self.client.perform_actions(mouse).await.expect("click");
    }

    /// Pointer down at `pixel` (the button stays down).
    pub async fn press_at(&self, pixel: (i64, i64)) {
        let mouse = MouseActions::new("mouse".to_owned())
            .then(move_to(pixel))
            .then(PointerAction::Down {
                button: MOUSE_BUTTON_LEFT,
            });
        self.client.perform_actions(mouse).await.expect("press");
    }

    /// A pointer move to `pixel` (with the button as it is).
    pub async fn move_to(&self, pixel: (i64, i64)) {
        let mouse = MouseActions::new("mouse".to_owned()).then(move_to(pixel));
        self.client.perform_actions(mouse).await.expect("move");
    }

    /// Pointer up where the pointer is.
    pub async fn release(&self) {
        let mouse = MouseActions::new("mouse".to_owned()).then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
        self.client.perform_actions(mouse).await.expect("release");
    }

    /// Drags the picked point: down on it, moves along `path` (pixels) at once (the page
    /// coalesces moves while a solve is in flight), up at the last one; waits for the commit.
    pub async fn drag(&self, from: (i64, i64), path: &[(i64, i64)]) {
        let mut mouse = MouseActions::new("mouse".to_owned())
            .then(move_to(from))
            .then(PointerAction::Down {
                button: MOUSE_BUTTON_LEFT,
            });
        for &pixel in path {
            mouse = mouse.then(move_to(pixel));
        }
        mouse = mouse.then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
        self.client.perform_actions(mouse).await.expect("drag");
        self.settle().await;
    }

    /// Ctrl+Z (undo) or, with `shift`, Ctrl+Shift+Z (redo).
    pub async fn ctrl_z(&self, shift: bool) {
        let control: char = Key::Control.into();
        let shift_key: char = Key::Shift.into();
        let mut keys =
            KeyActions::new("keyboard".to_owned()).then(KeyAction::Down { value: control });
        if shift {
            keys = keys.then(KeyAction::Down { value: shift_key });
        }
        keys = keys
            .then(KeyAction::Down { value: 'z' })
            .then(KeyAction::Up { value: 'z' });
        if shift {
            keys = keys.then(KeyAction::Up { value: shift_key });
        }
        keys = keys.then(KeyAction::Up { value: control });
        self.client.perform_actions(keys).await.expect("keys");
        self.settle().await;
    }

    /// Presses and releases `key` (a character, or a `Key` turned into one), with Shift
    /// held when `shift`.
    pub async fn key(&self, key: char, shift: bool) {
        let shift_key: char = Key::Shift.into();
        let mut keys = KeyActions::new("keyboard".to_owned());
        if shift {
            keys = keys.then(KeyAction::Down { value: shift_key });
        }
        keys = keys
            .then(KeyAction::Down { value: key })
            .then(KeyAction::Up { value: key });
        if shift {
            keys = keys.then(KeyAction::Up { value: shift_key });
        }
        self.client.perform_actions(keys).await.expect("key");
    }

    /// Holds `key` down (until [`Page::key_up`]).
    pub async fn key_down(&self, key: char) {
        let keys = KeyActions::new("keyboard".to_owned()).then(KeyAction::Down { value: key });
        self.client.perform_actions(keys).await.expect("key down");
    }

    /// Lets `key` go.
    pub async fn key_up(&self, key: char) {
        let keys = KeyActions::new("keyboard".to_owned()).then(KeyAction::Up { value: key });
        self.client.perform_actions(keys).await.expect("key up");
    }

    /// A wheel turn of `delta_y` pixels (negative: away from the user, zoom in) over `pixel`.
    pub async fn wheel_at(&self, pixel: (i64, i64), delta_y: i64) {
        let wheel = WheelActions::new("wheel".to_owned()).then(WheelAction::Scroll {
            duration: Some(Duration::from_millis(0)),
            x: pixel.0,
            y: pixel.1,
            delta_x: 0,
            delta_y,
        });
        self.client.perform_actions(wheel).await.expect("wheel");
    }

    /// Two fingers down at `a` and `b`, moved apart to `a_to` and `b_to` in `steps` steps,
    /// and lifted.
    pub async fn pinch(
        &self,
        (a, b): ((i64, i64), (i64, i64)),
        (a_to, b_to): ((i64, i64), (i64, i64)),
        steps: i64,
    ) {
        let finger = |name: &str, from: (i64, i64), to: (i64, i64)| {
            let mut touch =
                TouchActions::new(name.to_owned())
                    .then(move_to(from))
                    .then(PointerAction::Down {
                        button: MOUSE_BUTTON_LEFT,
                    });
            for step in 1..=steps {
                let at = (
                    from.0 + (to.0 - from.0) * step / steps,
                    from.1 + (to.1 - from.1) * step / steps,
                );
                touch = touch.then(move_to(at));
            }
            touch.then(PointerAction::Up {
                button: MOUSE_BUTTON_LEFT,
            })
        };
        let actions = fantoccini::actions::Actions::from(vec![
            fantoccini::actions::ActionSequence::from(finger("finger1", a, a_to)),
            fantoccini::actions::ActionSequence::from(finger("finger2", b, b_to)),
        ]);
        self.client.perform_actions(actions).await.expect("pinch");
    }

    /// Down at `from`, then every pixel of `path` as its own pointer move (chromedriver sends
    /// each once the page has taken the one before, once a frame: 60 Hz), then up.
    pub async fn drag_paced(&self, from: (i64, i64), path: &[(i64, i64)]) {
        let mut mouse = MouseActions::new("mouse".to_owned())
            .then(move_to(from))
            .then(PointerAction::Down {
                button: MOUSE_BUTTON_LEFT,
            });
        for &pixel in path {
            mouse = mouse.then(move_to(pixel));
        }
        mouse = mouse.then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
        self.client
            .perform_actions(mouse)
            .await
            .expect("paced drag");
    }

    /// The computed CSS `property` of the topmost element at viewport `pixel`.
    pub async fn style_at(&self, pixel: (i64, i64), property: &str) -> String {
        let value = self
            .run(
                "const e = document.elementFromPoint(arguments[0], arguments[1]); \
                 return e ? getComputedStyle(e).getPropertyValue(arguments[2]) : '';",
                vec![json!(pixel.0), json!(pixel.1), json!(property)],
            )
            .await;
        value.as_str().unwrap_or_default().to_owned()
    }

    /// The target of the drag in progress, or of the last edit (`body[data-target]`).
    pub async fn target(&self) -> [f64; 2] {
        let value: Value = serde_json::from_str(&self.data("target").await).expect("a target");
        [value[0].as_f64().unwrap(), value[1].as_f64().unwrap()]
    }

    /// The target of the drag in progress, or of the last edit, as the page sent it (3
    /// coordinates for a 3D curve).
    pub async fn target_sent(&self) -> Vec<f64> {
        serde_json::from_str(&self.data("target").await).expect("a target")
    }

    /// The view's frame `{scale, offset, fitted}` (`body[data-frame]`).
    pub async fn frame(&self) -> Value {
        serde_json::from_str(&self.data("frame").await).expect("data-frame is JSON")
    }

    /// The curve being edited (the committed one, or it with knots inserted for the pick).
    pub async fn edited(&self) -> Value {
        serde_json::from_str(&self.data("base").await).expect("data-base is JSON")
    }

    /// Clicks the element with `id`.
    pub async fn click_id(&self, id: &str) {
        self.client
            .find(Locator::Id(id))
            .await
            .unwrap_or_else(|error| panic!("#{id}: {error}"))
            .click()
            .await
            .unwrap_or_else(|error| panic!("click #{id}: {error}"));
    }
}

fn move_to(pixel: (i64, i64)) -> PointerAction {
    PointerAction::MoveTo {
        duration: Some(Duration::from_millis(0)),
        x: pixel.0 as f64,
        y: pixel.1 as f64,
    }
}
