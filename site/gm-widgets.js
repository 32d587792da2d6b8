/* The course website's widget set-up (tools/build_site.py copies it into _static/). It runs after
   require.js and before the widget manager (@jupyter-widgets/html-manager's embed-amd.js): the
   widget modules the manager does not bring itself are served by the site, so nothing is ever
   fetched from a CDN. jupyter-matplotlib is ipympl's front end, taken from the ipympl wheel. */
(function () {
  var me = document.currentScript;
  var base = me ? me.src.replace(/[^\/]*$/, '') : '_static/';
  // The widget manager's bundles find their fonts beside the module each is defined as
  // (@jupyter-widgets/controls, .../html-manager/dist/libembed-amd, ...): the site's widgets/.
  var paths = {'jupyter-matplotlib': base + 'ipympl/index', '@jupyter-widgets/html-manager/dist': base + 'widgets'};
  ['base', 'base7', 'controls', 'controls7', 'output', 'html-manager'].forEach(function (m) {
    paths['@jupyter-widgets/' + m] = base + 'widgets/' + m;
  });
  window.require.config({paths: paths});

  // ipywidgets' controls typeset their labels with MathJax 2's MathJax.Hub.Queue; the site runs
  // MathJax 3: give every MathJax object the page gets (the configuration first, then MathJax
  // itself) a Hub.Queue that typesets the element with MathJax 3.
  function hub(mj) {
    if (mj && typeof mj === 'object' && !mj.Hub) {
      mj.Hub = {Queue: function (job) {
        var el = job && job[2], m = window.MathJax;
        if (el && m && m.typesetPromise) m.typesetPromise([el]).catch(function () {});
      }};
    }
    return mj;
  }
  var current = hub(window.MathJax);
  Object.defineProperty(window, 'MathJax', {configurable: true, enumerable: true,
    get: function () { return current; }, set: function (v) { current = hub(v); }});
})();
