// The 3D view: a three.js renderer on the page's canvas, a perspective and an orthographic
// camera (toggled, the framing kept), orbit/pan/zoom by three.js's OrbitControls (orbit:
// drag; pan: Shift, middle or right button, or Space + drag; zoom about the pointer: wheel or
// pinch), the standard views, Fit, and the size of one pixel in the model at the focus (the
// meshes' tolerance follows it). It draws on demand: `request()` asks for one frame.

import * as THREE from "../../vendor/three/three.module.js";
import { OrbitControls } from "../../vendor/three/OrbitControls.js";

/** The perspective camera's vertical field of view, degrees. */
const FIELD_OF_VIEW = 35;

/** The share of the canvas's pixels (per side) drawn during a drag. */
const INTERACTIVE_RESOLUTION = 0.5;

/** Renderer names of WebGL drawn in software: SwiftShader (Chromium without a GPU), Mesa's
 * llvmpipe and softpipe, Windows' basic render driver. */
const SOFTWARE_RENDERER = /SwiftShader|llvmpipe|softpipe|Basic Render|Software/i;

/** Whether `gl` draws in software. Chromium names the renderer only through
 * `WEBGL_debug_renderer_info`; other browsers in `RENDERER` itself. */
function drawsInSoftware(gl) {
  const name = String(gl.getParameter(gl.RENDERER));
  if (SOFTWARE_RENDERER.test(name)) return true;
  if (!/^WebKit WebGL$/.test(name)) return false;
  const info = gl.getExtension("WEBGL_debug_renderer_info");
  return info !== null && SOFTWARE_RENDERER.test(String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)));
}

/** The standard views: the direction from the focus to the eye, and the up vector (z up, as
 * CAD models are drawn). */
export const VIEWS = {
  top: { eye: [0, 0, 1], up: [0, 1, 0] },
  bottom: { eye: [0, 0, -1], up: [0, 1, 0] },
  front: { eye: [0, -1, 0], up: [0, 0, 1] },
  back: { eye: [0, 1, 0], up: [0, 0, 1] },
  left: { eye: [-1, 0, 0], up: [0, 0, 1] },
  right: { eye: [1, 0, 0], up: [0, 0, 1] },
  isometric: { eye: [1, -1, 1], up: [0, 0, 1] },
};

/** Sets up the view on `canvas`; `onChange(kind)` hears "camera" while the view moves and
 * "settled" when a gesture ends. */
export function createView(canvas, onChange) {
  // No multisampling: the page must stay within a frame under software WebGL too (a
  // drag on a 30 × 30-pole surface, tests/editor/space.rs).
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, alpha: false, stencil: false });
  renderer.setPixelRatio(1);
  renderer.setClearColor(0xffffff, 1);
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8a96, 1.6));
  const perspective = new THREE.PerspectiveCamera(FIELD_OF_VIEW, 1, 0.01, 1000);
  const orthographic = new THREE.OrthographicCamera(-1, 1, 1, -1, -1000, 1000);
  const headlight = new THREE.DirectionalLight(0xffffff, 1.4);
  for (const camera of [perspective, orthographic]) {
    camera.up.set(0, 0, 1);
    scene.add(camera);
  }
  perspective.add(headlight);
  const controls = new OrbitControls(perspective, canvas);
  controls.zoomToCursor = true;
  controls.screenSpacePanning = true;
  controls.enableDamping = false;
  controls.mouseButtons = { LEFT: THREE.MOUSE.ROTATE, MIDDLE: THREE.MOUSE.PAN, RIGHT: THREE.MOUSE.PAN };
  controls.touches = { ONE: THREE.TOUCH.ROTATE, TWO: THREE.TOUCH.DOLLY_PAN };

  const view = {
    THREE,
    renderer,
    scene,
    controls,
    camera: perspective,
    perspective,
    orthographic,
    /** Half the orthographic frustum's height at zoom 1 (set by fit and the toggle). */
    orthographicHalfHeight: 1,
    size: { width: 1, height: 1 },
    /** The model's bounding sphere radius (set by fit): the cameras' near and far follow it. */
    radius: 1,
    pending: false,
    /** Milliseconds the last render took (the WebGL calls, not the GPU's raster). */
    lastRenderMs: 0,
    /** Whether WebGL draws in software here (finishFrame waits only then). */
    software: drawsInSoftware(renderer.getContext()),
  };

  const draw = () => {
    view.pending = false;
    const started = performance.now();
    renderer.render(scene, view.camera);
    view.lastRenderMs = performance.now() - started;
  };
  view.request = () => {
    if (view.pending) return;
    view.pending = true;
    requestAnimationFrame(() => {
      if (view.pending) draw();
    });
  };
  /** Renders now (a drag's preview: drawn in the same task as its answer); a frame already
   * requested is then not drawn again. */
  view.renderNow = () => draw();

  /** Draws the scene once with `group` in it (the warm-up of objects.js), waits until
   * the frame is rasterized, and takes `group` out again. */
  view.warmUp = (group) => {
    scene.add(group);
    draw();
    view.finishFrame();
    scene.remove(group);
    // The geometry goes; the materials' compiled programs stay for the objects' materials.
    group.traverse((object) => object.geometry?.dispose());
    view.request();
  };

  // A one-pixel read waits until the frame drawn so far is rasterized (WebGL's `finish()`
  // does not wait in Chromium).
  const onePixel = new Uint8Array(4);
  /** With WebGL in software, waits until the last frame is rasterized. A drag's preview
   * calls it right after drawing: otherwise the wait comes when the browser composites the
   * frame (Chromium without a GPU reads every WebGL frame back then, on the page's main
   * thread), at its next frame, where it holds up the next pointer event and answer.
   * Rasterizing a frame takes 5–9 ms in software; a GPU takes a fraction of one and its
   * frames are not read back, so there it does not wait. */
  view.finishFrame = () => {
    if (!view.software) return;
    const gl = renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, onePixel);
  };

  controls.addEventListener("change", () => {
    clipping(view);
    view.request();
    onChange("camera");
  });
  controls.addEventListener("end", () => onChange("settled"));

  view.resize = (width, height) => {
    if (width <= 0 || height <= 0) return;
    view.size = { width, height };
    renderer.setSize(width, height, false);
    perspective.aspect = width / height;
    perspective.updateProjectionMatrix();
    syncOrthographic(view);
    view.request();
  };

  /** While `on` (a drag), the canvas is drawn at `INTERACTIVE_RESOLUTION` of its pixels
   * and scaled up by the browser: software WebGL (and a browser compositing in software,
   * which copies every frame back to the page) costs in proportion to the pixels. */
  view.setInteractive = (on) => {
    const ratio = on ? INTERACTIVE_RESOLUTION : 1;
    if (renderer.getPixelRatio() === ratio) return;
    renderer.setPixelRatio(ratio);
    renderer.setSize(view.size.width, view.size.height, false);
    view.request();
  };

  view.setPerspective = (on) => {
    const from = view.camera;
    const to = on ? perspective : orthographic;
    if (from === to) return;
    to.position.copy(from.position);
    to.quaternion.copy(from.quaternion);
    to.up.copy(from.up);
    if (!on) {
      // The orthographic frustum shows what the perspective camera showed at the focus.
      orthographic.zoom = 1;
      const distance = perspective.position.distanceTo(controls.target);
      view.orthographicHalfHeight = distance * Math.tan(THREE.MathUtils.degToRad(FIELD_OF_VIEW / 2));
    }
    if (on) {
      // Keep the framing: the perspective eye at the distance that shows what the
      // orthographic camera showed.
      const shown = (orthographic.top - orthographic.bottom) / orthographic.zoom;
      const distance = shown / 2 / Math.tan(THREE.MathUtils.degToRad(FIELD_OF_VIEW / 2));
      const direction = new THREE.Vector3().subVectors(orthographic.position, controls.target).normalize();
      perspective.position.copy(controls.target).addScaledVector(direction, distance);
    }
    headlight.removeFromParent();
    to.add(headlight);
    view.camera = to;
    controls.object = to;
    syncOrthographic(view);
    clipping(view);
    controls.update();
    view.request();
    onChange("settled");
  };

  /** Frames the box `[min, max]` from the current direction (or `viewName`'s). */
  view.fit = (box, viewName = null) => {
    const min = new THREE.Vector3(...box[0]);
    const max = new THREE.Vector3(...box[1]);
    const centre = min.clone().add(max).multiplyScalar(0.5);
    const radius = Math.max(max.distanceTo(min) / 2, 1e-9);
    view.radius = radius;
    let direction;
    let up;
    if (viewName) {
      direction = new THREE.Vector3(...VIEWS[viewName].eye).normalize();
      up = new THREE.Vector3(...VIEWS[viewName].up);
    } else {
      direction = new THREE.Vector3().subVectors(view.camera.position, controls.target);
      if (direction.lengthSq() === 0) direction.set(1, -1, 1);
      direction.normalize();
      up = view.camera.up.clone();
    }
    const aspect = view.size.width / view.size.height;
    const halfAngle = THREE.MathUtils.degToRad(FIELD_OF_VIEW / 2);
    const distance = (radius / Math.sin(halfAngle)) * Math.max(1, 1 / aspect) * 1.05;
    controls.target.copy(centre);
    for (const camera of [perspective, orthographic]) {
      camera.up.copy(up);
      camera.position.copy(centre).addScaledVector(direction, distance);
      camera.lookAt(centre);
    }
    orthographic.zoom = 1;
    view.orthographicHalfHeight = distance * Math.tan(halfAngle);
    clipping(view);
    syncOrthographic(view);
    controls.update();
    view.request();
    onChange("settled");
  };

  /** The model length of one pixel at the focus (`controls.target`). */
  view.pixelSize = () => {
    if (view.camera.isOrthographicCamera) {
      return (orthographic.top - orthographic.bottom) / orthographic.zoom / view.size.height;
    }
    const distance = perspective.position.distanceTo(controls.target);
    return (2 * distance * Math.tan(THREE.MathUtils.degToRad(FIELD_OF_VIEW / 2))) / view.size.height;
  };

  /** The canvas pixel of model point `point` ([x, y] from the canvas's top left). */
  view.toPixel = (point) => {
    const projected = new THREE.Vector3(...point).project(view.camera);
    return [((projected.x + 1) / 2) * view.size.width, ((1 - projected.y) / 2) * view.size.height];
  };

  /** The ray through canvas pixel `[x, y]`. */
  view.rayAt = (pixel) => {
    const raycaster = new THREE.Raycaster();
    const ndc = new THREE.Vector2((pixel[0] / view.size.width) * 2 - 1, 1 - (pixel[1] / view.size.height) * 2);
    raycaster.setFromCamera(ndc, view.camera);
    return raycaster;
  };

  /** The unit vector from the eye into the view (the plane a drag moves in faces it). */
  view.viewDirection = () => view.camera.getWorldDirection(new THREE.Vector3());

  /** Plain numbers describing the camera (tests compare them before and after a gesture). */
  view.describe = () => ({
    position: view.camera.position.toArray(),
    target: controls.target.toArray(),
    up: view.camera.up.toArray(),
    zoom: view.camera.zoom,
    perspective: !view.camera.isOrthographicCamera,
  });

  return view;
}

/** The orthographic camera's frustum for the canvas's aspect. */
function syncOrthographic(view) {
  const camera = view.orthographic;
  const aspect = view.size.width / view.size.height;
  const half = view.orthographicHalfHeight;
  camera.left = -half * aspect;
  camera.right = half * aspect;
  camera.top = half;
  camera.bottom = -half;
  camera.updateProjectionMatrix();
}

/** Near and far planes that hold the model from any orbit. */
function clipping(view) {
  const distance = view.camera.position.distanceTo(view.controls.target);
  const perspective = view.camera.isPerspectiveCamera ? view.camera : null;
  if (perspective) {
    perspective.near = Math.max(distance / 1000, view.radius / 1e4);
    perspective.far = distance + 20 * view.radius;
    perspective.updateProjectionMatrix();
  } else {
    view.camera.near = -distance - 20 * view.radius;
    view.camera.far = distance + 20 * view.radius;
    view.camera.updateProjectionMatrix();
  }
}
