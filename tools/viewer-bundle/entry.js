// The part of three.js the design review page (geargen/report/viewer/review.js) uses, as one
// global THREE: Chromium loads neither ES modules nor fetch() from file://, so the page gets a
// classic script. Add a name here when review.js starts to use it, then `npm run build`.
import {
  Box3, DirectionalLight, HemisphereLight, PerspectiveCamera, Plane, Raycaster, Scene, Sphere, Vector2, Vector3,
  WebGLRenderer,
} from "three";
import { GLTFLoader } from "three/addons/loaders/GLTFLoader.js";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

globalThis.THREE = {
  Box3, DirectionalLight, HemisphereLight, PerspectiveCamera, Plane, Raycaster, Scene, Sphere, Vector2, Vector3,
  WebGLRenderer, GLTFLoader, OrbitControls,
};
